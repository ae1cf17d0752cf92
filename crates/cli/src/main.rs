//! The `hdot` command-line tool.
//!
//! Each subcommand lives in a module of its own under `cmd/`, with a clap
//! `Args` struct and a `run` function returning the process exit code.
//! Exit codes: 0 success; 1 a check or verification failed, or a result
//! could not be written; 2 bad input (a file that does not parse, an
//! unknown name, an invalid option). A standard output closed by its reader
//! (`hdot list | head -1`) ends the command quietly with 0; a closed
//! standard error loses the message, not the exit code (`errln!`).

use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod catalog;
mod cmd;
mod html;
mod output;
mod review;

/// Derive, print, check and verify the equations of three-dimensional
/// rigid-body kinetics.
#[derive(Debug, Parser)]
#[command(name = "hdot", version, about, long_about = None, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

// `defer`: a subcommand's arguments are built only when it runs or its help
// is shown, not the thirteen of them at every start (docs/performance.md).
// Its one-line doc comment below is its `about`: the `Args` structs in
// `cmd/` carry `//` comments, since a deferred struct's doc comment would
// replace that line in the help.
#[derive(Debug, Subcommand)]
#[command(defer = true)]
enum Command {
    // -- subcommands (one line each; keep alphabetical within a group) --
    /// Run derivations and check their expectations; print a table.
    Check(cmd::check::CheckArgs),
    /// Discretised inertia against analytic: orders, charts, cheapest for --tol.
    Convergence(cmd::convergence::ConvergenceArgs),
    /// Derive one derivation's equations and print them in textbook form.
    Derive(cmd::derive::DeriveArgs),
    /// What changed in the mathematics of derivation files, step by step.
    Diff(cmd::diff::DiffArgs),
    /// H_G, H_O, T, required resultants and solved unknowns of a scene.
    Dynamics(cmd::dynamics::DynamicsArgs),
    /// Mass, centre, inertia about G and O, principal axes of a scene.
    Inertia(cmd::inertia::InertiaArgs),
    /// List the bundled derivations with title and source.
    List(cmd::list::ListArgs),
    /// Write the lecture notes (LaTeX and Markdown) of every derivation.
    Notes(cmd::notes::NotesArgs),
    /// Simulate a scene with the least exact model; report error, drift and cost.
    Simulate(cmd::simulate::SimulateArgs),
    /// One review file per derivation; --check fails when one would change.
    Snapshot(cmd::snapshot::SnapshotArgs),
    /// Eigenvalues of linearised equations over a parameter; where they are stable.
    Stability(cmd::stability::StabilityArgs),
    /// Derived equations against particle sums on random bodies and states.
    Verify(cmd::verify::VerifyArgs),
    /// Sweep every method over steps and tolerances; write CSV and chart.
    WorkPrecision(cmd::work_precision::WorkPrecisionArgs),
}

/// Stack of the thread a command runs on. Parsing and evaluation are
/// bounded in depth (see `hdot_sym::parse::MAX_DEPTH`); this is a margin
/// for the deepest expression they allow, in unoptimised builds too.
const STACK_BYTES: usize = 256 << 20;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let worker = std::thread::Builder::new()
        .name("hdot".into())
        .stack_size(STACK_BYTES)
        .spawn(move || dispatch(cli));
    match worker.map(|w| w.join()) {
        Ok(Ok(code)) => code,
        // The panic message is already on stderr.
        Ok(Err(_)) => ExitCode::from(101),
        Err(e) => {
            crate::errln!("error: cannot start: {e}");
            ExitCode::from(2)
        }
    }
}

fn dispatch(cli: Cli) -> ExitCode {
    let result: anyhow::Result<ExitCode> = match cli.command {
        // -- dispatch (one line each) --
        Command::Check(a) => cmd::check::run(a),
        Command::Convergence(a) => cmd::convergence::run(a),
        Command::Derive(a) => cmd::derive::run(a),
        Command::Diff(a) => cmd::diff::run(a),
        Command::Dynamics(a) => cmd::dynamics::run(a),
        Command::Inertia(a) => cmd::inertia::run(a),
        Command::List(a) => cmd::list::run(a),
        Command::Notes(a) => cmd::notes::run(a),
        Command::Simulate(a) => cmd::simulate::run(a),
        Command::Snapshot(a) => cmd::snapshot::run(a),
        Command::Stability(a) => cmd::stability::run(a),
        Command::Verify(a) => cmd::verify::run(a),
        Command::WorkPrecision(a) => cmd::work_precision::run(a),
    };
    match result {
        Ok(code) => code,
        Err(err) => match err.downcast_ref::<output::OutputError>() {
            Some(o) if o.is_closed_stdout() => ExitCode::SUCCESS,
            Some(o) if o.is_input_refusal() => {
                crate::errln!("error: {err:#}");
                ExitCode::from(2)
            }
            Some(_) => {
                crate::errln!("error: {err:#}");
                ExitCode::from(1)
            }
            None => {
                crate::errln!("error: {err:#}");
                ExitCode::from(2)
            }
        },
    }
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    /// Building a deferred subcommand (as running it or its `--help` does)
    /// keeps the line `hdot --help` lists for it: no `Args` struct's doc
    /// comment replaces it, and every subcommand has one.
    #[test]
    fn deferred_subcommands_keep_their_about() {
        let listed: Vec<(String, String)> = super::Cli::command()
            .get_subcommands()
            .map(|c| {
                let about = c.get_about().map(ToString::to_string).unwrap_or_default();
                (c.get_name().to_owned(), about)
            })
            .collect();
        let mut built = super::Cli::command();
        built.build();
        for (name, about) in listed {
            assert!(
                !about.is_empty(),
                "`hdot {name}` has no one-line description"
            );
            let sub = built.find_subcommand(&name).expect("listed");
            assert_eq!(
                sub.get_about().map(ToString::to_string),
                Some(about),
                "`hdot {name} --help`"
            );
            assert!(
                sub.get_long_about().is_none(),
                "`hdot {name}` has a long description"
            );
        }
    }
}
