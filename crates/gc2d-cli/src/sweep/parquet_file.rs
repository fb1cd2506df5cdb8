//! The table as Parquet (zstd-compressed, one row group): `point` and `outcome` as UTF-8 strings, each parameter as a
//! double where all its values are numbers and as a string otherwise, `seed` as an unsigned 64-bit integer and every
//! result as an optional double. Written through parquet's column writers, without arrow arrays (see Cargo.toml).

use super::SweepError;
use super::collect::Table;
use super::spec::SEED;
use parquet::basic::{Compression, LogicalType, Repetition, Type as Physical, ZstdLevel};
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::errors::ParquetError;
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;
use std::path::Path;
use std::sync::Arc;

/// One column's values.
enum Column {
    /// Strings, `None` for null.
    Text(Vec<Option<String>>),
    /// Doubles, `None` for null.
    Number(Vec<Option<f64>>),
    /// The seeds.
    Seed(Vec<u64>),
}

/// Writes `table` to `path`.
pub fn write_parquet(table: &Table, path: &Path) -> Result<(), SweepError> {
    write(table, path).map_err(|e| SweepError::failed(format!("cannot write {}: {e}", path.display())))
}

fn write(table: &Table, path: &Path) -> Result<(), ParquetError> {
    let rows = &table.rows;
    let mut columns: Vec<(String, Column)> =
        vec![("point".into(), Column::Text(rows.iter().map(|r| Some(r.point.clone())).collect()))];
    for (k, name) in table.parameters.iter().enumerate() {
        let texts: Vec<&str> = rows.iter().map(|r| r.parameters[k].as_str()).collect();
        let numbers: Option<Vec<f64>> = texts.iter().map(|t| t.parse().ok()).collect();
        let column = match numbers {
            Some(numbers) => Column::Number(numbers.into_iter().map(Some).collect()),
            None => Column::Text(texts.iter().map(|t| Some(t.trim_matches('"').to_owned())).collect()),
        };
        columns.push((name.clone(), column));
    }
    columns.push((SEED.into(), Column::Seed(rows.iter().map(|r| r.seed).collect())));
    columns.push(("outcome".into(), Column::Text(rows.iter().map(|r| r.outcome.clone()).collect())));
    for name in &table.numbers {
        columns.push((name.clone(), Column::Number(rows.iter().map(|r| r.numbers.get(name).copied()).collect())));
    }

    let fields = columns.iter().map(|(name, column)| field(name, column).map(Arc::new)).collect::<Result<_, _>>()?;
    let schema = Arc::new(Type::group_type_builder("sweep").with_fields(fields).build()?);
    let properties =
        Arc::new(WriterProperties::builder().set_compression(Compression::ZSTD(ZstdLevel::default())).build());
    let file = std::fs::File::create(path)?;
    let mut writer = SerializedFileWriter::new(file, schema, properties)?;
    let mut group = writer.next_row_group()?;
    for (_, column) in &columns {
        let Some(mut out) = group.next_column()? else { break };
        match column {
            Column::Text(values) => {
                let (present, levels) = split(values);
                let bytes: Vec<ByteArray> = present.into_iter().map(|s| ByteArray::from(s.as_str())).collect();
                out.typed::<ByteArrayType>().write_batch(&bytes, Some(&levels), None)?;
            }
            Column::Number(values) => {
                let (present, levels) = split(values);
                let present: Vec<f64> = present.into_iter().copied().collect();
                out.typed::<DoubleType>().write_batch(&present, Some(&levels), None)?;
            }
            Column::Seed(values) => {
                // Parquet stores unsigned 64-bit integers in INT64 with the unsigned logical type (bit-identical).
                let values: Vec<i64> = values.iter().map(|&s| s as i64).collect();
                out.typed::<Int64Type>().write_batch(&values, None, None)?;
            }
        }
        out.close()?;
    }
    group.close()?;
    writer.close()?;
    Ok(())
}

/// The Parquet field of a column.
fn field(name: &str, column: &Column) -> Result<Type, ParquetError> {
    match column {
        Column::Text(_) => Type::primitive_type_builder(name, Physical::BYTE_ARRAY)
            .with_repetition(Repetition::OPTIONAL)
            .with_logical_type(Some(LogicalType::String))
            .build(),
        Column::Number(_) => {
            Type::primitive_type_builder(name, Physical::DOUBLE).with_repetition(Repetition::OPTIONAL).build()
        }
        Column::Seed(_) => Type::primitive_type_builder(name, Physical::INT64)
            .with_repetition(Repetition::REQUIRED)
            .with_logical_type(Some(LogicalType::Integer { bit_width: 64, is_signed: false }))
            .build(),
    }
}

/// The present values and the definition levels (1 present, 0 null) of an optional column.
fn split<T>(values: &[Option<T>]) -> (Vec<&T>, Vec<i16>) {
    let present = values.iter().flatten().collect();
    let levels = values.iter().map(|v| i16::from(v.is_some())).collect();
    (present, levels)
}
