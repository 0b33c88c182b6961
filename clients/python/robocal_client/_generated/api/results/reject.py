from http import HTTPStatus
from typing import Any, cast
from urllib.parse import quote

import httpx

from ...client import AuthenticatedClient, Client
from ...types import Response, UNSET
from ... import errors

from ...models.decision_body import DecisionBody
from ...models.hand_eye_set_out import HandEyeSetOut
from ...models.kinematic_set_out import KinematicSetOut
from ...models.problem import Problem
from ...models.stage_camera_set_out import StageCameraSetOut
from ...types import UNSET, Unset
from typing import cast



def _get_kwargs(
    serial: str,
    version: str,
    *,
    body: DecisionBody | Unset = UNSET,

) -> dict[str, Any]:
    headers: dict[str, Any] = {}


    

    

    _kwargs: dict[str, Any] = {
        "method": "post",
        "url": "/v1/robots/{serial}/parameter-sets/{version}/reject".format(serial=quote(str(serial), safe=""),version=quote(str(version), safe=""),),
    }

    
    if not isinstance(body, Unset):
        _kwargs["json"] = body.to_dict()

    headers["Content-Type"] = "application/json"

    _kwargs["headers"] = headers
    return _kwargs



def _parse_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> HandEyeSetOut | KinematicSetOut | StageCameraSetOut | Problem | None:
    if response.status_code == 200:
        def _parse_response_200(data: object) -> HandEyeSetOut | KinematicSetOut | StageCameraSetOut:
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                componentsschemas_parameter_set_out_type_0 = KinematicSetOut.from_dict(data)



                return componentsschemas_parameter_set_out_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                componentsschemas_parameter_set_out_type_1 = HandEyeSetOut.from_dict(data)



                return componentsschemas_parameter_set_out_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            if not isinstance(data, dict):
                raise TypeError()
            componentsschemas_parameter_set_out_type_2 = StageCameraSetOut.from_dict(data)



            return componentsschemas_parameter_set_out_type_2

        response_200 = _parse_response_200(response.json())

        return response_200

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


def _build_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> Response[HandEyeSetOut | KinematicSetOut | StageCameraSetOut | Problem]:
    return Response(
        status_code=HTTPStatus(response.status_code),
        content=response.content,
        headers=response.headers,
        parsed=_parse_response(client=client, response=response),
    )


def sync_detailed(
    serial: str,
    version: str,
    *,
    client: AuthenticatedClient | Client,
    body: DecisionBody | Unset = UNSET,

) -> Response[HandEyeSetOut | KinematicSetOut | StageCameraSetOut | Problem]:
    """ Reject a parameter set: kept for the record, never served as `latest`.

    Args:
        serial (str):
        version (str):
        body (DecisionBody | Unset): `approve` / `reject` body; optional.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[HandEyeSetOut | KinematicSetOut | StageCameraSetOut | Problem]
     """


    kwargs = _get_kwargs(
        serial=serial,
version=version,
body=body,

    )

    response = client.get_httpx_client().request(
        **kwargs,
    )

    return _build_response(client=client, response=response)

def sync(
    serial: str,
    version: str,
    *,
    client: AuthenticatedClient | Client,
    body: DecisionBody | Unset = UNSET,

) -> HandEyeSetOut | KinematicSetOut | StageCameraSetOut | Problem | None:
    """ Reject a parameter set: kept for the record, never served as `latest`.

    Args:
        serial (str):
        version (str):
        body (DecisionBody | Unset): `approve` / `reject` body; optional.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        HandEyeSetOut | KinematicSetOut | StageCameraSetOut | Problem
     """


    return sync_detailed(
        serial=serial,
version=version,
client=client,
body=body,

    ).parsed

async def asyncio_detailed(
    serial: str,
    version: str,
    *,
    client: AuthenticatedClient | Client,
    body: DecisionBody | Unset = UNSET,

) -> Response[HandEyeSetOut | KinematicSetOut | StageCameraSetOut | Problem]:
    """ Reject a parameter set: kept for the record, never served as `latest`.

    Args:
        serial (str):
        version (str):
        body (DecisionBody | Unset): `approve` / `reject` body; optional.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[HandEyeSetOut | KinematicSetOut | StageCameraSetOut | Problem]
     """


    kwargs = _get_kwargs(
        serial=serial,
version=version,
body=body,

    )

    response = await client.get_async_httpx_client().request(
        **kwargs
    )

    return _build_response(client=client, response=response)

async def asyncio(
    serial: str,
    version: str,
    *,
    client: AuthenticatedClient | Client,
    body: DecisionBody | Unset = UNSET,

) -> HandEyeSetOut | KinematicSetOut | StageCameraSetOut | Problem | None:
    """ Reject a parameter set: kept for the record, never served as `latest`.

    Args:
        serial (str):
        version (str):
        body (DecisionBody | Unset): `approve` / `reject` body; optional.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        HandEyeSetOut | KinematicSetOut | StageCameraSetOut | Problem
     """


    return (await asyncio_detailed(
        serial=serial,
version=version,
client=client,
body=body,

    )).parsed
