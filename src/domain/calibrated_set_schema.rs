//! The OpenAPI schema of a calibrated set, built from the variants' own
//! types: `oneOf` the three documents, each carrying its `kind`, with
//! `kind` as the discriminator, so a generated client gets one class per
//! variant and reads `kind` to pick it. The served set with its identity
//! (`api::results::ParameterSetOut`) uses the same helpers.

use utoipa::openapi::schema::{
    AllOfBuilder, Discriminator, ObjectBuilder, OneOfBuilder, Schema, Type,
};
use utoipa::openapi::{Ref, RefOr};
use utoipa::{PartialSchema, ToSchema};

use super::calibrated_set::{HAND_EYE, KIND_KEY, KINEMATIC, STAGE_CAMERA};
use super::{CalibratedSet, HandEyeSet, ParameterSet, StageCameraSet};

/// Named schemas as `ToSchema::schemas` collects them.
pub type Schemas = Vec<(String, RefOr<Schema>)>;

/// Each variant's `kind` and its name in `components/schemas`.
pub const SET_SCHEMAS: [(&str, &str); 3] = [
    (KINEMATIC, "KinematicSet"),
    (HAND_EYE, "HandEyeSet"),
    (STAGE_CAMERA, "StageCameraSet"),
];

/// `schema` (an object) with the required property `kind`, whose one
/// value is `kind`.
fn with_kind(schema: RefOr<Schema>, kind: &str) -> RefOr<Schema> {
    match schema {
        RefOr::T(Schema::Object(mut object)) => {
            let tag = ObjectBuilder::new()
                .schema_type(Type::String)
                .enum_values(Some([kind]))
                .description(Some("What the set identified (the variant's tag)."))
                .build();
            object.properties.insert(KIND_KEY.into(), tag.into());
            object.required.push(KIND_KEY.into());
            RefOr::T(Schema::Object(object))
        }
        other => other,
    }
}

/// `oneOf` the named schemas, told apart by `kind`: `variants` are
/// (`kind`, schema name).
pub fn tagged_one_of(variants: &[(&str, &str)], description: &str) -> RefOr<Schema> {
    let mapping = variants
        .iter()
        .map(|(kind, name)| (*kind, format!("#/components/schemas/{name}")));
    let mut one_of = OneOfBuilder::new()
        .description(Some(description))
        .discriminator(Some(Discriminator::with_mapping(KIND_KEY, mapping)));
    for (_, name) in variants {
        one_of = one_of.item(Ref::from_schema_name(*name));
    }
    RefOr::T(Schema::OneOf(one_of.build()))
}

/// `allOf` the named schemas: an object with every one's properties.
pub fn all_of(names: &[&str]) -> RefOr<Schema> {
    let mut all = AllOfBuilder::new();
    for name in names {
        all = all.item(Ref::from_schema_name(*name));
    }
    RefOr::T(Schema::AllOf(all.build()))
}

impl PartialSchema for CalibratedSet {
    fn schema() -> RefOr<Schema> {
        tagged_one_of(
            &SET_SCHEMAS,
            "A calibrated parameter set: a robot model (`kinematic`), a hand–eye \
             (`hand_eye`) or a camera calibrated on a stage (`stage_camera`).",
        )
    }
}

impl ToSchema for CalibratedSet {
    fn schemas(schemas: &mut Schemas) {
        let [kinematic, hand_eye, stage_camera] = SET_SCHEMAS;
        schemas.push((
            kinematic.1.into(),
            with_kind(ParameterSet::schema(), kinematic.0),
        ));
        <ParameterSet as ToSchema>::schemas(schemas);
        schemas.push((
            hand_eye.1.into(),
            with_kind(HandEyeSet::schema(), hand_eye.0),
        ));
        <HandEyeSet as ToSchema>::schemas(schemas);
        schemas.push((
            stage_camera.1.into(),
            with_kind(StageCameraSet::schema(), stage_camera.0),
        ));
        <StageCameraSet as ToSchema>::schemas(schemas);
    }
}
