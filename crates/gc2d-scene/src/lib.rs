pub mod gsi;
