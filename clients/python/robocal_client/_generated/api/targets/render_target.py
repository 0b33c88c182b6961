from http import HTTPStatus
from typing import Any, cast
from urllib.parse import quote

import httpx

from ...client import AuthenticatedClient, Client
from ...types import Response, UNSET
from ... import errors

from ...models.problem import Problem
from ...types import UNSET, Unset
from typing import cast



def _get_kwargs(
    *,
    kind: str | Unset = UNSET,
    rows: int | Unset = UNSET,
    cols: int | Unset = UNSET,
    pitch_mm: float | Unset = UNSET,
    dot_diameter_mm: float | Unset = UNSET,
    origin_marker_diameter_mm: float | Unset = UNSET,
    squares: str | Unset = UNSET,
    square_mm: float | Unset = UNSET,
    inner_corners: str | Unset = UNSET,
    marker_mm: float | Unset = UNSET,
    dictionary: str | Unset = UNSET,
    legacy_layout: bool | Unset = UNSET,
    format_: str | Unset = UNSET,
    page: str | Unset = UNSET,

) -> dict[str, Any]:
    

    

    params: dict[str, Any] = {}

    params["kind"] = kind

    params["rows"] = rows

    params["cols"] = cols

    params["pitch_mm"] = pitch_mm

    params["dot_diameter_mm"] = dot_diameter_mm

    params["origin_marker_diameter_mm"] = origin_marker_diameter_mm

    params["squares"] = squares

    params["square_mm"] = square_mm

    params["inner_corners"] = inner_corners

    params["marker_mm"] = marker_mm

    params["dictionary"] = dictionary

    params["legacy_layout"] = legacy_layout

    params["format"] = format_

    params["page"] = page


    params = {k: v for k, v in params.items() if v is not UNSET and v is not None}


    _kwargs: dict[str, Any] = {
        "method": "get",
        "url": "/v1/targets/render",
        "params": params,
    }


    return _kwargs



def _parse_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> Problem | str | None:
    if response.status_code == 200:
        response_200 = response.text
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


def _build_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> Response[Problem | str]:
    return Response(
        status_code=HTTPStatus(response.status_code),
        content=response.content,
        headers=response.headers,
        parsed=_parse_response(client=client, response=response),
    )


def sync_detailed(
    *,
    client: AuthenticatedClient | Client,
    kind: str | Unset = UNSET,
    rows: int | Unset = UNSET,
    cols: int | Unset = UNSET,
    pitch_mm: float | Unset = UNSET,
    dot_diameter_mm: float | Unset = UNSET,
    origin_marker_diameter_mm: float | Unset = UNSET,
    squares: str | Unset = UNSET,
    square_mm: float | Unset = UNSET,
    inner_corners: str | Unset = UNSET,
    marker_mm: float | Unset = UNSET,
    dictionary: str | Unset = UNSET,
    legacy_layout: bool | Unset = UNSET,
    format_: str | Unset = UNSET,
    page: str | Unset = UNSET,

) -> Response[Problem | str]:
    """ A target drawn 1:1 on the smallest ISO sheet that holds it (or scaled to
    fill the sheet `page` names), with a scale bar and the session `target`
    spec in the margin.

    Args:
        kind (str | Unset):
        rows (int | Unset):
        cols (int | Unset):
        pitch_mm (float | Unset):
        dot_diameter_mm (float | Unset):
        origin_marker_diameter_mm (float | Unset):
        squares (str | Unset):
        square_mm (float | Unset):
        inner_corners (str | Unset):
        marker_mm (float | Unset):
        dictionary (str | Unset):
        legacy_layout (bool | Unset):
        format_ (str | Unset):
        page (str | Unset):

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[Problem | str]
     """


    kwargs = _get_kwargs(
        kind=kind,
rows=rows,
cols=cols,
pitch_mm=pitch_mm,
dot_diameter_mm=dot_diameter_mm,
origin_marker_diameter_mm=origin_marker_diameter_mm,
squares=squares,
square_mm=square_mm,
inner_corners=inner_corners,
marker_mm=marker_mm,
dictionary=dictionary,
legacy_layout=legacy_layout,
format_=format_,
page=page,

    )

    response = client.get_httpx_client().request(
        **kwargs,
    )

    return _build_response(client=client, response=response)

def sync(
    *,
    client: AuthenticatedClient | Client,
    kind: str | Unset = UNSET,
    rows: int | Unset = UNSET,
    cols: int | Unset = UNSET,
    pitch_mm: float | Unset = UNSET,
    dot_diameter_mm: float | Unset = UNSET,
    origin_marker_diameter_mm: float | Unset = UNSET,
    squares: str | Unset = UNSET,
    square_mm: float | Unset = UNSET,
    inner_corners: str | Unset = UNSET,
    marker_mm: float | Unset = UNSET,
    dictionary: str | Unset = UNSET,
    legacy_layout: bool | Unset = UNSET,
    format_: str | Unset = UNSET,
    page: str | Unset = UNSET,

) -> Problem | str | None:
    """ A target drawn 1:1 on the smallest ISO sheet that holds it (or scaled to
    fill the sheet `page` names), with a scale bar and the session `target`
    spec in the margin.

    Args:
        kind (str | Unset):
        rows (int | Unset):
        cols (int | Unset):
        pitch_mm (float | Unset):
        dot_diameter_mm (float | Unset):
        origin_marker_diameter_mm (float | Unset):
        squares (str | Unset):
        square_mm (float | Unset):
        inner_corners (str | Unset):
        marker_mm (float | Unset):
        dictionary (str | Unset):
        legacy_layout (bool | Unset):
        format_ (str | Unset):
        page (str | Unset):

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Problem | str
     """


    return sync_detailed(
        client=client,
kind=kind,
rows=rows,
cols=cols,
pitch_mm=pitch_mm,
dot_diameter_mm=dot_diameter_mm,
origin_marker_diameter_mm=origin_marker_diameter_mm,
squares=squares,
square_mm=square_mm,
inner_corners=inner_corners,
marker_mm=marker_mm,
dictionary=dictionary,
legacy_layout=legacy_layout,
format_=format_,
page=page,

    ).parsed

async def asyncio_detailed(
    *,
    client: AuthenticatedClient | Client,
    kind: str | Unset = UNSET,
    rows: int | Unset = UNSET,
    cols: int | Unset = UNSET,
    pitch_mm: float | Unset = UNSET,
    dot_diameter_mm: float | Unset = UNSET,
    origin_marker_diameter_mm: float | Unset = UNSET,
    squares: str | Unset = UNSET,
    square_mm: float | Unset = UNSET,
    inner_corners: str | Unset = UNSET,
    marker_mm: float | Unset = UNSET,
    dictionary: str | Unset = UNSET,
    legacy_layout: bool | Unset = UNSET,
    format_: str | Unset = UNSET,
    page: str | Unset = UNSET,

) -> Response[Problem | str]:
    """ A target drawn 1:1 on the smallest ISO sheet that holds it (or scaled to
    fill the sheet `page` names), with a scale bar and the session `target`
    spec in the margin.

    Args:
        kind (str | Unset):
        rows (int | Unset):
        cols (int | Unset):
        pitch_mm (float | Unset):
        dot_diameter_mm (float | Unset):
        origin_marker_diameter_mm (float | Unset):
        squares (str | Unset):
        square_mm (float | Unset):
        inner_corners (str | Unset):
        marker_mm (float | Unset):
        dictionary (str | Unset):
        legacy_layout (bool | Unset):
        format_ (str | Unset):
        page (str | Unset):

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[Problem | str]
     """


    kwargs = _get_kwargs(
        kind=kind,
rows=rows,
cols=cols,
pitch_mm=pitch_mm,
dot_diameter_mm=dot_diameter_mm,
origin_marker_diameter_mm=origin_marker_diameter_mm,
squares=squares,
square_mm=square_mm,
inner_corners=inner_corners,
marker_mm=marker_mm,
dictionary=dictionary,
legacy_layout=legacy_layout,
format_=format_,
page=page,

    )

    response = await client.get_async_httpx_client().request(
        **kwargs
    )

    return _build_response(client=client, response=response)

async def asyncio(
    *,
    client: AuthenticatedClient | Client,
    kind: str | Unset = UNSET,
    rows: int | Unset = UNSET,
    cols: int | Unset = UNSET,
    pitch_mm: float | Unset = UNSET,
    dot_diameter_mm: float | Unset = UNSET,
    origin_marker_diameter_mm: float | Unset = UNSET,
    squares: str | Unset = UNSET,
    square_mm: float | Unset = UNSET,
    inner_corners: str | Unset = UNSET,
    marker_mm: float | Unset = UNSET,
    dictionary: str | Unset = UNSET,
    legacy_layout: bool | Unset = UNSET,
    format_: str | Unset = UNSET,
    page: str | Unset = UNSET,

) -> Problem | str | None:
    """ A target drawn 1:1 on the smallest ISO sheet that holds it (or scaled to
    fill the sheet `page` names), with a scale bar and the session `target`
    spec in the margin.

    Args:
        kind (str | Unset):
        rows (int | Unset):
        cols (int | Unset):
        pitch_mm (float | Unset):
        dot_diameter_mm (float | Unset):
        origin_marker_diameter_mm (float | Unset):
        squares (str | Unset):
        square_mm (float | Unset):
        inner_corners (str | Unset):
        marker_mm (float | Unset):
        dictionary (str | Unset):
        legacy_layout (bool | Unset):
        format_ (str | Unset):
        page (str | Unset):

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Problem | str
     """


    return (await asyncio_detailed(
        client=client,
kind=kind,
rows=rows,
cols=cols,
pitch_mm=pitch_mm,
dot_diameter_mm=dot_diameter_mm,
origin_marker_diameter_mm=origin_marker_diameter_mm,
squares=squares,
square_mm=square_mm,
inner_corners=inner_corners,
marker_mm=marker_mm,
dictionary=dictionary,
legacy_layout=legacy_layout,
format_=format_,
page=page,

    )).parsed
