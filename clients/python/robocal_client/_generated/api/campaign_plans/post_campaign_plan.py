from http import HTTPStatus
from typing import Any, cast
from urllib.parse import quote

import httpx

from ...client import AuthenticatedClient, Client
from ...types import Response, UNSET
from ... import errors

from ...models.campaign_plan_body import CampaignPlanBody
from ...models.campaign_plan_out import CampaignPlanOut
from ...models.problem import Problem
from typing import cast



def _get_kwargs(
    serial: str,
    *,
    body: CampaignPlanBody,

) -> dict[str, Any]:
    headers: dict[str, Any] = {}


    

    

    _kwargs: dict[str, Any] = {
        "method": "post",
        "url": "/v1/robots/{serial}/campaign-plans".format(serial=quote(str(serial), safe=""),),
    }

    _kwargs["json"] = body.to_dict()

    headers["Content-Type"] = "application/json"

    _kwargs["headers"] = headers
    return _kwargs



def _parse_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> CampaignPlanOut | Problem | None:
    if response.status_code == 201:
        response_201 = CampaignPlanOut.from_dict(response.json())



        return response_201

    if response.status_code == 400:
        response_400 = Problem.from_dict(response.json())



        return response_400

    if response.status_code == 401:
        response_401 = Problem.from_dict(response.json())



        return response_401

    if response.status_code == 403:
        response_403 = Problem.from_dict(response.json())



        return response_403

    if response.status_code == 404:
        response_404 = Problem.from_dict(response.json())



        return response_404

    if response.status_code == 408:
        response_408 = Problem.from_dict(response.json())



        return response_408

    if response.status_code == 413:
        response_413 = Problem.from_dict(response.json())



        return response_413

    if response.status_code == 415:
        response_415 = Problem.from_dict(response.json())



        return response_415

    if response.status_code == 422:
        response_422 = Problem.from_dict(response.json())



        return response_422

    if response.status_code == 503:
        response_503 = Problem.from_dict(response.json())



        return response_503

    if client.raise_on_unexpected_status:
        raise errors.UnexpectedStatus(response.status_code, response.content)
    else:
        return None


def _build_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> Response[CampaignPlanOut | Problem]:
    return Response(
        status_code=HTTPStatus(response.status_code),
        content=response.content,
        headers=response.headers,
        parsed=_parse_response(client=client, response=response),
    )


def sync_detailed(
    serial: str,
    *,
    client: AuthenticatedClient | Client,
    body: CampaignPlanBody,

) -> Response[CampaignPlanOut | Problem]:
    """ Plan a campaign: the calibration (and validation) poses to shoot, in a
    short joint-space order, with the predicted validation error. Uses the
    robot's latest parameter set's kinematics, else its nominal table.

    Args:
        serial (str):
        body (CampaignPlanBody): `POST /v1/robots/{serial}/campaign-plans` body.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[CampaignPlanOut | Problem]
     """


    kwargs = _get_kwargs(
        serial=serial,
body=body,

    )

    response = client.get_httpx_client().request(
        **kwargs,
    )

    return _build_response(client=client, response=response)

def sync(
    serial: str,
    *,
    client: AuthenticatedClient | Client,
    body: CampaignPlanBody,

) -> CampaignPlanOut | Problem | None:
    """ Plan a campaign: the calibration (and validation) poses to shoot, in a
    short joint-space order, with the predicted validation error. Uses the
    robot's latest parameter set's kinematics, else its nominal table.

    Args:
        serial (str):
        body (CampaignPlanBody): `POST /v1/robots/{serial}/campaign-plans` body.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        CampaignPlanOut | Problem
     """


    return sync_detailed(
        serial=serial,
client=client,
body=body,

    ).parsed

async def asyncio_detailed(
    serial: str,
    *,
    client: AuthenticatedClient | Client,
    body: CampaignPlanBody,

) -> Response[CampaignPlanOut | Problem]:
    """ Plan a campaign: the calibration (and validation) poses to shoot, in a
    short joint-space order, with the predicted validation error. Uses the
    robot's latest parameter set's kinematics, else its nominal table.

    Args:
        serial (str):
        body (CampaignPlanBody): `POST /v1/robots/{serial}/campaign-plans` body.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[CampaignPlanOut | Problem]
     """


    kwargs = _get_kwargs(
        serial=serial,
body=body,

    )

    response = await client.get_async_httpx_client().request(
        **kwargs
    )

    return _build_response(client=client, response=response)

async def asyncio(
    serial: str,
    *,
    client: AuthenticatedClient | Client,
    body: CampaignPlanBody,

) -> CampaignPlanOut | Problem | None:
    """ Plan a campaign: the calibration (and validation) poses to shoot, in a
    short joint-space order, with the predicted validation error. Uses the
    robot's latest parameter set's kinematics, else its nominal table.

    Args:
        serial (str):
        body (CampaignPlanBody): `POST /v1/robots/{serial}/campaign-plans` body.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        CampaignPlanOut | Problem
     """


    return (await asyncio_detailed(
        serial=serial,
client=client,
body=body,

    )).parsed
