//! One module per subcommand, each with a clap `Args` struct and
//! `run(args) -> anyhow::Result<ExitCode>`.
pub mod check;
pub mod convergence;
pub mod derive;
pub mod diff;
pub mod dynamics;
pub mod inertia;
pub mod list;
pub mod notes;
pub mod simulate;
pub mod snapshot;
pub mod stability;
pub mod verify;
pub mod work_precision;
