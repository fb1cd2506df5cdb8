//! Tables as Parquet files (zstd-compressed, one row group), the format pandas, polars and DuckDB read: the sweep's
//! result table and the exported particle and contact tables. Written through parquet's column writers, without
//! arrow arrays (see the workspace Cargo.toml: arrow would add minutes of build for nothing we need).

use parquet::basic::{Compression, LogicalType, Repetition, Type as Physical, ZstdLevel};
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::errors::ParquetError;
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;
use std::path::Path;
use std::sync::Arc;

/// One column's values, all of one type.
#[derive(Debug, Clone, PartialEq)]
pub enum ParquetColumn {
    /// UTF-8 strings, `None` for null.
    Text(Vec<Option<String>>),
    /// Doubles, `None` for null.
    Number(Vec<Option<f64>>),
    /// Unsigned integers (stored as INT64 with the unsigned logical type, bit-identical), never null.
    Unsigned(Vec<u64>),
}

/// A named column.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedColumn {
    /// The column's name.
    pub name: String,
    /// Its values.
    pub values: ParquetColumn,
}

impl NamedColumn {
    /// A column of doubles, none null.
    pub fn numbers(name: &str, values: impl IntoIterator<Item = f64>) -> Self {
        Self { name: name.into(), values: ParquetColumn::Number(values.into_iter().map(Some).collect()) }
    }

    /// A column of strings, none null.
    pub fn texts(name: &str, values: impl IntoIterator<Item = String>) -> Self {
        Self { name: name.into(), values: ParquetColumn::Text(values.into_iter().map(Some).collect()) }
    }

    /// A column of unsigned integers.
    pub fn unsigned(name: &str, values: impl IntoIterator<Item = u64>) -> Self {
        Self { name: name.into(), values: ParquetColumn::Unsigned(values.into_iter().collect()) }
    }
}

/// Writes the columns (of equal length) as the table `table_name` to `path`.
pub fn write_parquet(table_name: &str, columns: &[NamedColumn], path: &Path) -> Result<(), ParquetError> {
    let fields = columns.iter().map(|c| field(c).map(Arc::new)).collect::<Result<_, _>>()?;
    let schema = Arc::new(Type::group_type_builder(table_name).with_fields(fields).build()?);
    let properties =
        Arc::new(WriterProperties::builder().set_compression(Compression::ZSTD(ZstdLevel::default())).build());
    let file = std::fs::File::create(path)?;
    let mut writer = SerializedFileWriter::new(file, schema, properties)?;
    let mut group = writer.next_row_group()?;
    for column in columns {
        let Some(mut out) = group.next_column()? else { break };
        match &column.values {
            ParquetColumn::Text(values) => {
                let (present, levels) = split(values);
                let bytes: Vec<ByteArray> = present.into_iter().map(|s| ByteArray::from(s.as_str())).collect();
                out.typed::<ByteArrayType>().write_batch(&bytes, Some(&levels), None)?;
            }
            ParquetColumn::Number(values) => {
                let (present, levels) = split(values);
                let present: Vec<f64> = present.into_iter().copied().collect();
                out.typed::<DoubleType>().write_batch(&present, Some(&levels), None)?;
            }
            ParquetColumn::Unsigned(values) => {
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
fn field(column: &NamedColumn) -> Result<Type, ParquetError> {
    let name = column.name.as_str();
    match column.values {
        ParquetColumn::Text(_) => Type::primitive_type_builder(name, Physical::BYTE_ARRAY)
            .with_repetition(Repetition::OPTIONAL)
            .with_logical_type(Some(LogicalType::String))
            .build(),
        ParquetColumn::Number(_) => {
            Type::primitive_type_builder(name, Physical::DOUBLE).with_repetition(Repetition::OPTIONAL).build()
        }
        ParquetColumn::Unsigned(_) => Type::primitive_type_builder(name, Physical::INT64)
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
