from http import HTTPStatus
from typing import Any, cast
from urllib.parse import quote

import httpx

from ...client import AuthenticatedClient, Client
from ...types import Response, UNSET
from ... import errors

from ...models.compensate_request import CompensateRequest
from ...models.compensate_response import CompensateResponse
from ...models.problem import Problem
from ...types import UNSET, Unset
from typing import cast



def _get_kwargs(
    serial: str,
    version: str,
    *,
    body: CompensateRequest,
    controller_serial: str | Unset = UNSET,

) -> dict[str, Any]:
    headers: dict[str, Any] = {}


    

    params: dict[str, Any] = {}

    params["controller_serial"] = controller_serial


    params = {k: v for k, v in params.items() if v is not UNSET and v is not None}


    _kwargs: dict[str, Any] = {
        "method": "post",
        "url": "/v1/robots/{serial}/parameter-sets/{version}/compensate".format(serial=quote(str(serial), safe=""),version=quote(str(version), safe=""),),
        "params": params,
    }

    _kwargs["json"] = body.to_dict()

    headers["Content-Type"] = "application/json"

    _kwargs["headers"] = headers
    return _kwargs



def _parse_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> CompensateResponse | Problem | None:
    if response.status_code == 200:
        response_200 = CompensateResponse.from_dict(response.json())



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

    if response.status_code == 409:
        response_409 = Problem.from_dict(response.json())



        return response_409

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


def _build_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> Response[CompensateResponse | Problem]:
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
    body: CompensateRequest,
    controller_serial: str | Unset = UNSET,

) -> Response[CompensateResponse | Problem]:
    """ Joints that put the tool on each target according to the calibrated
    model. With `Accept: application/x-ndjson` the answer streams, one line
    per target (as `filter`).

    Args:
        serial (str):
        version (str):
        controller_serial (str | Unset):
        body (CompensateRequest):

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[CompensateResponse | Problem]
     """


    kwargs = _get_kwargs(
        serial=serial,
version=version,
body=body,
controller_serial=controller_serial,

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
    body: CompensateRequest,
    controller_serial: str | Unset = UNSET,

) -> CompensateResponse | Problem | None:
    """ Joints that put the tool on each target according to the calibrated
    model. With `Accept: application/x-ndjson` the answer streams, one line
    per target (as `filter`).

    Args:
        serial (str):
        version (str):
        controller_serial (str | Unset):
        body (CompensateRequest):

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        CompensateResponse | Problem
     """


    return sync_detailed(
        serial=serial,
version=version,
client=client,
body=body,
controller_serial=controller_serial,

    ).parsed

async def asyncio_detailed(
    serial: str,
    version: str,
    *,
    client: AuthenticatedClient | Client,
    body: CompensateRequest,
    controller_serial: str | Unset = UNSET,

) -> Response[CompensateResponse | Problem]:
    """ Joints that put the tool on each target according to the calibrated
    model. With `Accept: application/x-ndjson` the answer streams, one line
    per target (as `filter`).

    Args:
        serial (str):
        version (str):
        controller_serial (str | Unset):
        body (CompensateRequest):

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[CompensateResponse | Problem]
     """


    kwargs = _get_kwargs(
        serial=serial,
version=version,
body=body,
controller_serial=controller_serial,

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
    body: CompensateRequest,
    controller_serial: str | Unset = UNSET,

) -> CompensateResponse | Problem | None:
    """ Joints that put the tool on each target according to the calibrated
    model. With `Accept: application/x-ndjson` the answer streams, one line
    per target (as `filter`).

    Args:
        serial (str):
        version (str):
        controller_serial (str | Unset):
        body (CompensateRequest):

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        CompensateResponse | Problem
     """


    return (await asyncio_detailed(
        serial=serial,
version=version,
client=client,
body=body,
controller_serial=controller_serial,

    )).parsed
