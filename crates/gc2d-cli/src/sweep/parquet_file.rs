//! The table as Parquet (crate::parquet_table): `point` and `outcome` as UTF-8 strings, each parameter as a double
//! where all its values are numbers and as a string otherwise, `seed` as an unsigned 64-bit integer and every result
//! as an optional double.

use super::collect::Table;
use super::spec::SEED;
use crate::failure::CommandFailure;
use crate::parquet_table::{NamedColumn, ParquetColumn, write_parquet as write_table};
use std::path::Path;

/// Writes `table` to `path`.
pub fn write_parquet(table: &Table, path: &Path) -> Result<(), CommandFailure> {
    let rows = &table.rows;
    let text = |name: &str, values: Vec<Option<String>>| NamedColumn {
        name: name.into(),
        values: ParquetColumn::Text(values),
    };
    let mut columns = vec![text("point", rows.iter().map(|r| Some(r.point.clone())).collect())];
    for (k, name) in table.parameters.iter().enumerate() {
        let texts: Vec<&str> = rows.iter().map(|r| r.parameters[k].as_str()).collect();
        let numbers: Option<Vec<f64>> = texts.iter().map(|t| t.parse().ok()).collect();
        columns.push(match numbers {
            Some(numbers) => NamedColumn::numbers(name, numbers),
            None => text(name, texts.iter().map(|t| Some(t.trim_matches('"').to_owned())).collect()),
        });
    }
    columns.push(NamedColumn::unsigned(SEED, rows.iter().map(|r| r.seed)));
    columns.push(text("outcome", rows.iter().map(|r| r.outcome.clone()).collect()));
    for name in &table.numbers {
        let values = rows.iter().map(|r| r.numbers.get(name).copied()).collect();
        columns.push(NamedColumn { name: name.clone(), values: ParquetColumn::Number(values) });
    }
    write_table("sweep", &columns, path)
        .map_err(|e| CommandFailure::failed(format!("cannot write {}: {e}", path.display())))
}
