//! Campaign plans (issue 16), written once for both backends.

use async_trait::async_trait;

use crate::store::backend::Backend;
use crate::store::rows::{json, Columns};
use crate::store::statement::query;
use crate::store::{CampaignPlanRecord, CampaignPlanStore, StoreResult};

#[async_trait]
impl<B: Backend> CampaignPlanStore for B {
    async fn insert_campaign_plan(&self, plan: &CampaignPlanRecord) -> StoreResult<()> {
        query(
            "INSERT INTO campaign_plans (id, serial, request, plan, created_at)
             VALUES ($1, $2, $3, $4, $5)",
        )
        .bind(plan.id.as_str())
        .bind(plan.serial.as_str())
        .bind(plan.request.to_string())
        .bind(plan.plan.to_string())
        .bind(plan.created_at.as_str())
        .execute(self.pool())
        .await?;
        Ok(())
    }

    async fn get_campaign_plan(
        &self,
        serial: &str,
        id: &str,
    ) -> StoreResult<Option<CampaignPlanRecord>> {
        let row = query(
            "SELECT id, serial, request, plan, created_at FROM campaign_plans
             WHERE serial = $1 AND id = $2",
        )
        .bind(serial)
        .bind(id)
        .fetch_optional(self.pool())
        .await?;
        row.map(|r| {
            Ok(CampaignPlanRecord {
                id: r.string("id"),
                serial: r.string("serial"),
                request: json(r.str("request"))?,
                plan: json(r.str("plan"))?,
                created_at: r.string("created_at"),
            })
        })
        .transpose()
    }
}
