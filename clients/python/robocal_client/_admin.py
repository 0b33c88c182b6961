"""Campaign plans, re-checks, webhooks and tokens."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ._base import Base, as_model
from ._generated.api.campaign_plans import get_campaign_plan, post_campaign_plan
from ._generated.api.jobs import start_check
from ._generated.api.tokens import create_token, list_tokens, revoke_token
from ._generated.api.webhooks import create_webhook, delete_webhook, get_webhook, list_webhooks
from ._generated.models import (
    CampaignPlanBody,
    CampaignPlanOut,
    CheckBody,
    JobAccepted,
    TokenBody,
    TokenCreated,
    TokenList,
    WebhookBody,
    WebhookCreated,
    WebhookList,
    WebhookOut,
)
from ._generated.types import UNSET
from ._http import expect_no_content, unwrap


class AdminMixin(Base):
    # Campaign plans ---------------------------------------------------
    def plan(self, serial: str, body: CampaignPlanBody | Mapping[str, Any]) -> CampaignPlanOut:
        """Poses to measure, chosen so the parameters are identifiable."""
        answer = post_campaign_plan.sync_detailed(serial, client=self.api, body=as_model(CampaignPlanBody, body))
        return unwrap(answer, CampaignPlanOut)

    def get_plan(self, serial: str, plan_id: str) -> CampaignPlanOut:
        return unwrap(get_campaign_plan.sync_detailed(serial, plan_id, client=self.api), CampaignPlanOut)

    # Re-checks --------------------------------------------------------
    def check(self, session_id: str, body: CheckBody | Mapping[str, Any] | None = None) -> JobAccepted:
        """Queue a re-check of the latest approved set against a short
        session; `wait` for the job, whose result holds the verdict."""
        checked = UNSET if body is None else as_model(CheckBody, body)
        return unwrap(start_check.sync_detailed(session_id, client=self.api, body=checked), JobAccepted)

    # Webhooks ---------------------------------------------------------
    def create_webhook(self, url: str, events: list[str]) -> WebhookCreated:
        """Its `secret` (for the signature) is in this answer only."""
        answer = create_webhook.sync_detailed(client=self.api, body=WebhookBody(url=url, events=events))
        return unwrap(answer, WebhookCreated)

    def list_webhooks(self) -> WebhookList:
        return unwrap(list_webhooks.sync_detailed(client=self.api), WebhookList)

    def get_webhook(self, webhook_id: str) -> WebhookOut:
        return unwrap(get_webhook.sync_detailed(webhook_id, client=self.api), WebhookOut)

    def delete_webhook(self, webhook_id: str) -> None:
        expect_no_content(delete_webhook.sync_detailed(webhook_id, client=self.api))

    # Tokens -----------------------------------------------------------
    def create_token(self, name: str, scope: str, expires_in_secs: int | None = None) -> TokenCreated:
        """A new bearer token; its secret (`token`) is in this answer only."""
        body = TokenBody(name=name, scope=scope, expires_in_secs=UNSET if expires_in_secs is None else expires_in_secs)
        return unwrap(create_token.sync_detailed(client=self.api, body=body), TokenCreated)

    def list_tokens(self) -> TokenList:
        return unwrap(list_tokens.sync_detailed(client=self.api), TokenList)

    def revoke_token(self, token_id: str) -> None:
        expect_no_content(revoke_token.sync_detailed(token_id, client=self.api))
