//! The controller's flange pose of one camera pose (issue 14, "Poses from
//! the controller"): where the robot says its flange was, in the base frame,
//! instead of the joint angles. The document form only; its typed,
//! checked form is [`crate::domain::FlangePose`].

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// The flange in the robot base frame (`base_to_flange`): `translation_mm`
/// and either `rotation_deg` (fixed-axis X-Y-Z angles in degrees,
/// `R = Rz(rz) Ry(ry) Rx(rx)`, as every pose of the contract) or `matrix`
/// (the 3x3 rotation, row-major, orthonormal with determinant +1), not both.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct FlangePoseDoc {
    #[schema(min_items = 3, max_items = 3)]
    pub translation_mm: [f64; 3],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(min_items = 3, max_items = 3)]
    pub rotation_deg: Option<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(schema_with = matrix3_schema)]
    pub matrix: Option<[[f64; 3]; 3]>,
}

/// The schema of an optional 3x3 row-major rotation.
fn matrix3_schema() -> utoipa::openapi::schema::Array {
    optional_matrix_schema(
        3,
        "3x3 row-major rotation of the flange in the base frame (instead of rotation_deg)",
    )
}

/// The schema of an optional `side`x`side` row-major matrix: `side` rows of
/// `side` numbers (serde reads fixed-size arrays, any other length is
/// refused), with its description.
pub fn optional_matrix_schema(side: usize, description: &str) -> utoipa::openapi::schema::Array {
    use utoipa::openapi::schema::{ArrayBuilder, ObjectBuilder, SchemaType, Type};
    let row = ArrayBuilder::new()
        .items(ObjectBuilder::new().schema_type(Type::Number))
        .min_items(Some(side))
        .max_items(Some(side));
    ArrayBuilder::new()
        .schema_type(SchemaType::from_iter([Type::Array, Type::Null]))
        .items(row)
        .min_items(Some(side))
        .max_items(Some(side))
        .description(Some(description))
        .build()
}
