//! Migrations compiled into the binary (each backend lists its own
//! `migrations/<backend>/` files), so a deployed binary needs no files.

use std::borrow::Cow;

use sqlx::migrate::{Migration, MigrationType, Migrator};

/// One migration: version, description, SQL.
pub type Embedded = (i64, &'static str, &'static str);

/// A `sqlx` migrator over `list`, with `sqlx`'s defaults (as
/// `Migrator::new` would build from a directory).
pub fn migrator(list: &'static [Embedded]) -> Migrator {
    let migrations: Vec<Migration> = list
        .iter()
        .map(|(version, name, sql)| {
            Migration::new(
                *version,
                Cow::Borrowed(*name),
                MigrationType::Simple,
                Cow::Borrowed(*sql),
                false,
            )
        })
        .collect();
    Migrator {
        migrations: Cow::Owned(migrations),
        ..Migrator::DEFAULT
    }
}
