//! The ensemble statistics of a sweep: its completed points grouped by their parameter values, and every numeric
//! column's mean and sample standard deviation over each group's seeds (`sweep_means.csv`). For an ensemble without
//! parameters that is one row: the ensemble's means and spreads (the pile's mean flank angle ± its spread).

use super::collect::{Table, number};
use super::plots::mean_and_sd;
use crate::failure::CommandFailure;
use gc2d_analysis::particle_state::csv::quoted;
use std::collections::HashMap;
use std::path::Path;

/// One group of points: the same parameter values, different seeds.
#[derive(Debug, Clone, PartialEq)]
pub struct SeedGroup {
    /// The parameter values as written in the scene.
    pub parameters: Vec<String>,
    /// Its completed points.
    pub seeds: usize,
    /// Per numeric column of the table, in its order: the mean and sample standard deviation over the completed
    /// points that have the value (`None` where none has it; the deviation `None` where fewer than two have it).
    pub statistics: Vec<Option<(f64, Option<f64>)>>,
}

/// The groups of the table's completed points, in the order of their first point. Points that did not complete are
/// left out: an interrupted or failed run's numbers are not its point's result.
pub fn seed_groups(table: &Table) -> Vec<SeedGroup> {
    let mut groups: Vec<(Vec<String>, Vec<usize>)> = Vec::new();
    let mut group_of: HashMap<&[String], usize> = HashMap::new();
    for (index, row) in table.rows.iter().enumerate() {
        if row.outcome.as_deref() != Some("completed") {
            continue;
        }
        let group = *group_of.entry(&row.parameters).or_insert_with(|| {
            groups.push((row.parameters.clone(), Vec::new()));
            groups.len() - 1
        });
        groups[group].1.push(index);
    }
    groups
        .into_iter()
        .map(|(parameters, members)| {
            let statistics = table
                .numbers
                .iter()
                .map(|name| {
                    let values: Vec<f64> = members
                        .iter()
                        .filter_map(|&i| table.rows[i].numbers.get(name).copied())
                        .filter(|v| v.is_finite())
                        .collect();
                    (!values.is_empty()).then(|| {
                        let (mean, sd) = mean_and_sd(&values);
                        (mean, (values.len() > 1).then_some(sd))
                    })
                })
                .collect();
            SeedGroup { parameters, seeds: members.len(), statistics }
        })
        .collect()
}

/// Writes the groups as CSV: the parameters, `seeds`, then `<column>.mean` and `<column>.sd` for every numeric
/// column of the table (empty where there is no value, or no spread of a single one).
pub fn write_means_csv(table: &Table, groups: &[SeedGroup], path: &Path) -> Result<(), CommandFailure> {
    let mut header: Vec<String> = table.parameters.iter().map(|p| quoted(p).into_owned()).collect();
    header.push("seeds".to_owned());
    for name in &table.numbers {
        header.push(quoted(&format!("{name}.mean")).into_owned());
        header.push(quoted(&format!("{name}.sd")).into_owned());
    }
    let mut text = header.join(",");
    text.push('\n');
    for group in groups {
        let mut fields: Vec<String> =
            group.parameters.iter().map(|v| quoted(v.trim_matches('"')).into_owned()).collect();
        fields.push(group.seeds.to_string());
        for statistic in &group.statistics {
            let (mean, sd) = statistic.map_or((None, None), |(mean, sd)| (Some(mean), sd));
            fields.push(mean.map_or(String::new(), number));
            fields.push(sd.map_or(String::new(), number));
        }
        text.push_str(&fields.join(","));
        text.push('\n');
    }
    std::fs::write(path, text).map_err(|e| CommandFailure::failed(format!("cannot write {}: {e}", path.display())))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::collect::Row;

    fn row(mu: &str, seed: u64, outcome: &str, angle: Option<f64>) -> Row {
        Row {
            point: format!("mu={mu}_seed={seed}"),
            parameters: vec![mu.to_owned()],
            seed,
            outcome: Some(outcome.to_owned()),
            numbers: angle.map(|a| ("angle".to_owned(), a)).into_iter().collect::<HashMap<_, _>>(),
        }
    }

    #[test]
    fn completed_seeds_are_averaged_per_parameter_value() {
        let table = Table {
            parameters: vec!["mu".into()],
            numbers: vec!["angle".into()],
            rows: vec![
                row("0.3", 1, "completed", Some(20.0)),
                row("0.6", 1, "completed", Some(30.0)),
                row("0.3", 2, "completed", Some(22.0)),
                row("0.6", 2, "interrupted", Some(99.0)),
                row("0.3", 3, "completed", None),
            ],
        };
        let groups = seed_groups(&table);
        assert_eq!(groups.len(), 2);
        assert_eq!((groups[0].parameters[0].as_str(), groups[0].seeds), ("0.3", 3));
        assert_eq!(groups[0].statistics[0], Some((21.0, Some(2f64.sqrt()))));
        // The interrupted point is left out: one value, no spread.
        assert_eq!((groups[1].seeds, groups[1].statistics[0]), (1, Some((30.0, None))));

        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("means.csv");
        write_means_csv(&table, &groups, &path).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(text, format!("mu,seeds,angle.mean,angle.sd\n0.3,3,21,{}\n0.6,1,30,\n", number(2f64.sqrt())));
    }
}
