from http import HTTPStatus
from typing import Any, cast
from urllib.parse import quote

import httpx

from ...client import AuthenticatedClient, Client
from ...types import Response, UNSET, Unset
from ... import errors

from ...models.pose_image_upload import PoseImageUpload
from ...models.pose_json_body import PoseJsonBody
from ...models.pose_out import PoseOut
from ...models.problem import Problem
from typing import cast



def _get_kwargs(
    id: str,
    *,
    body:    PoseJsonBody  |     PoseImageUpload  | Unset = UNSET,

) -> dict[str, Any]:
    headers: dict[str, Any] = {}


    

    

    _kwargs: dict[str, Any] = {
        "method": "post",
        "url": "/v1/sessions/{id}/poses".format(id=quote(str(id), safe=""),),
    }

    if isinstance(body, PoseJsonBody):
        _kwargs["json"] = body.to_dict()

        headers["Content-Type"] = "application/json"
    if isinstance(body, PoseImageUpload):
        _kwargs["files"] = body.to_multipart()


    _kwargs["headers"] = headers
    return _kwargs



def _parse_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> PoseOut | Problem | None:
    if response.status_code == 201:
        response_201 = PoseOut.from_dict(response.json())



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


def _build_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> Response[PoseOut | Problem]:
    return Response(
        status_code=HTTPStatus(response.status_code),
        content=response.content,
        headers=response.headers,
        parsed=_parse_response(client=client, response=response),
    )


def sync_detailed(
    id: str,
    *,
    client: AuthenticatedClient | Client,
    body:    PoseJsonBody  |     PoseImageUpload  | Unset = UNSET,

) -> Response[PoseOut | Problem]:
    """ Add one pose: `multipart/form-data` (parts `joints_deg` or
    `flange_pose`, or for a stage session `stage_position_mm` and
    `sequence`; `set`, `group`, `image`) or JSON with `image_points` (camera) or `measured_position_mm`
    (tracker).

    Args:
        id (str):
        body (PoseJsonBody): `POST /v1/sessions/{id}/poses` JSON body.
        body (PoseImageUpload): The `multipart/form-data` pose upload (its schema; the parts are
            read
            one by one in `add_pose`).

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[PoseOut | Problem]
     """


    kwargs = _get_kwargs(
        id=id,
body=body,

    )

    response = client.get_httpx_client().request(
        **kwargs,
    )

    return _build_response(client=client, response=response)

def sync(
    id: str,
    *,
    client: AuthenticatedClient | Client,
    body:    PoseJsonBody  |     PoseImageUpload  | Unset = UNSET,

) -> PoseOut | Problem | None:
    """ Add one pose: `multipart/form-data` (parts `joints_deg` or
    `flange_pose`, or for a stage session `stage_position_mm` and
    `sequence`; `set`, `group`, `image`) or JSON with `image_points` (camera) or `measured_position_mm`
    (tracker).

    Args:
        id (str):
        body (PoseJsonBody): `POST /v1/sessions/{id}/poses` JSON body.
        body (PoseImageUpload): The `multipart/form-data` pose upload (its schema; the parts are
            read
            one by one in `add_pose`).

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        PoseOut | Problem
     """


    return sync_detailed(
        id=id,
client=client,
body=body,

    ).parsed

async def asyncio_detailed(
    id: str,
    *,
    client: AuthenticatedClient | Client,
    body:    PoseJsonBody  |     PoseImageUpload  | Unset = UNSET,

) -> Response[PoseOut | Problem]:
    """ Add one pose: `multipart/form-data` (parts `joints_deg` or
    `flange_pose`, or for a stage session `stage_position_mm` and
    `sequence`; `set`, `group`, `image`) or JSON with `image_points` (camera) or `measured_position_mm`
    (tracker).

    Args:
        id (str):
        body (PoseJsonBody): `POST /v1/sessions/{id}/poses` JSON body.
        body (PoseImageUpload): The `multipart/form-data` pose upload (its schema; the parts are
            read
            one by one in `add_pose`).

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[PoseOut | Problem]
     """


    kwargs = _get_kwargs(
        id=id,
body=body,

    )

    response = await client.get_async_httpx_client().request(
        **kwargs
    )

    return _build_response(client=client, response=response)

async def asyncio(
    id: str,
    *,
    client: AuthenticatedClient | Client,
    body:    PoseJsonBody  |     PoseImageUpload  | Unset = UNSET,

) -> PoseOut | Problem | None:
    """ Add one pose: `multipart/form-data` (parts `joints_deg` or
    `flange_pose`, or for a stage session `stage_position_mm` and
    `sequence`; `set`, `group`, `image`) or JSON with `image_points` (camera) or `measured_position_mm`
    (tracker).

    Args:
        id (str):
        body (PoseJsonBody): `POST /v1/sessions/{id}/poses` JSON body.
        body (PoseImageUpload): The `multipart/form-data` pose upload (its schema; the parts are
            read
            one by one in `add_pose`).

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        PoseOut | Problem
     """


    return (await asyncio_detailed(
        id=id,
client=client,
body=body,

    )).parsed
