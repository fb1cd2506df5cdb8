//! Runs the convergence study: `cargo run -p gc2d-validation --release --example convergence -- OUT_DIR [--quick]`.
//! (The `gc2d-rs convergence` subcommand calls the same function.)

use gc2d_validation::{ConvergenceOptions, run_convergence};
use std::path::PathBuf;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let out_dir =
        args.iter().find(|a| !a.starts_with("--")).map_or_else(|| PathBuf::from("convergence"), PathBuf::from);
    match run_convergence(&ConvergenceOptions { out_dir, quick }) {
        Ok(report) => {
            for file in &report.files {
                println!("{}", file.display());
            }
        }
        Err(error) => {
            eprintln!("convergence study failed: {error}");
            std::process::exit(1);
        }
    }
}
