//! One module per subcommand, each with a clap `Args` struct and
//! `run(args) -> anyhow::Result<ExitCode>`.
