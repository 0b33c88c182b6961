from http import HTTPStatus
from typing import Any, cast
from urllib.parse import quote

import httpx

from ...client import AuthenticatedClient, Client
from ...types import Response, UNSET
from ... import errors

from ...models.problem import Problem
from ...models.session_body import SessionBody
from ...models.session_out import SessionOut
from typing import cast



def _get_kwargs(
    serial: str,
    *,
    body: SessionBody,

) -> dict[str, Any]:
    headers: dict[str, Any] = {}


    

    

    _kwargs: dict[str, Any] = {
        "method": "post",
        "url": "/v1/robots/{serial}/sessions".format(serial=quote(str(serial), safe=""),),
    }

    _kwargs["json"] = body.to_dict()

    headers["Content-Type"] = "application/json"

    _kwargs["headers"] = headers
    return _kwargs



def _parse_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> Problem | SessionOut | None:
    if response.status_code == 201:
        response_201 = SessionOut.from_dict(response.json())



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


def _build_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> Response[Problem | SessionOut]:
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
    body: SessionBody,

) -> Response[Problem | SessionOut]:
    """ Open a measurement session for a robot.

    Args:
        serial (str):
        body (SessionBody): `POST /v1/robots/{serial}/sessions` body.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[Problem | SessionOut]
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
    body: SessionBody,

) -> Problem | SessionOut | None:
    """ Open a measurement session for a robot.

    Args:
        serial (str):
        body (SessionBody): `POST /v1/robots/{serial}/sessions` body.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Problem | SessionOut
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
    body: SessionBody,

) -> Response[Problem | SessionOut]:
    """ Open a measurement session for a robot.

    Args:
        serial (str):
        body (SessionBody): `POST /v1/robots/{serial}/sessions` body.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[Problem | SessionOut]
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
    body: SessionBody,

) -> Problem | SessionOut | None:
    """ Open a measurement session for a robot.

    Args:
        serial (str):
        body (SessionBody): `POST /v1/robots/{serial}/sessions` body.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Problem | SessionOut
     """


    return (await asyncio_detailed(
        serial=serial,
client=client,
body=body,

    )).parsed
