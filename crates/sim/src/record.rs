//! The one integrate-and-record loop every integrated model runs through
//! ([`integrate_recorded`]): rows streamed as CSV or stored within a
//! memory budget, progress reported; and the timing of a sweep run.

use std::io::Write;
use std::time::Instant;

use crate::{Limits, Method, SimError, Stats, Step, integrate};

/// Output options of a run.
pub struct Output<'a> {
    /// Stream every accepted step as a CSV row to this writer.
    pub stream: Option<&'a mut dyn Write>,
    /// Keep the trajectory in the report.
    pub store: bool,
    /// Budget in bytes for the stored trajectory.
    pub memory_budget: u64,
    /// Called after every step of each of the run's integrations with
    /// what is integrated (`run`, `reference run`, `pilot run`) and the
    /// time it reached, so that a long reference or pilot shows too.
    pub progress: Option<Progress<'a>>,
}

/// A run's progress callback: what is integrated (`run`, `reference run`,
/// `pilot run`) and the time it reached.
pub type Progress<'a> = &'a mut dyn FnMut(&str, f64);

impl Default for Output<'_> {
    fn default() -> Self {
        Output {
            stream: None,
            store: false,
            memory_budget: 64 << 20,
            progress: None,
        }
    }
}

/// Bytes one stored row of `len` numbers takes (values and vector header).
fn row_bytes(len: usize) -> u64 {
    (len * 8 + 24) as u64
}

/// Columns a streamed row carries after the recorded ones, computed
/// from the row (`[t, y…]`): a derived scene's bodies' positions.
pub type Columns<'c> = &'c dyn Fn(&[f64]) -> Vec<f64>;

/// Records streamed/stored rows and progress inside the integrator's observer.
pub struct Recorder<'a, 'b> {
    out: &'b mut Output<'a>,
    rows: Vec<Vec<f64>>,
    bytes: u64,
    columns: Option<Columns<'b>>,
}

impl<'a, 'b> Recorder<'a, 'b> {
    /// A recorder writing to `out`.
    pub(crate) fn new(out: &'b mut Output<'a>) -> Self {
        Recorder {
            out,
            rows: vec![],
            bytes: 0,
            columns: None,
        }
    }

    /// Streams `columns` of each row after the row itself (the stored
    /// trajectory keeps the row alone).
    pub(crate) fn with_columns(mut self, columns: Columns<'b>) -> Self {
        self.columns = Some(columns);
        self
    }

    /// Streams, stores and reports one row `[t, …]`.
    pub fn record(&mut self, row: Vec<f64>) -> Result<(), SimError> {
        self.tick("run", row[0]);
        if let Some(w) = self.out.stream.as_mut() {
            let extra = self.columns.map(|f| f(&row)).unwrap_or_default();
            // `+ 0.0` turns −0 into 0: a streamed row never reads `-0e0`.
            let line: Vec<String> = row
                .iter()
                .chain(&extra)
                .map(|v| format!("{:e}", v + 0.0))
                .collect();
            writeln!(w, "{}", line.join(",")).map_err(SimError::Output)?;
        }
        if self.out.store {
            self.bytes += row_bytes(row.len());
            if self.bytes > self.out.memory_budget {
                return Err(SimError::MemoryBudget {
                    needed: self.bytes,
                    budget: self.out.memory_budget,
                });
            }
            self.rows.push(row);
        }
        Ok(())
    }

    /// Reports that the integration `what` reached `t` (to the progress
    /// callback, when there is one).
    pub fn tick(&mut self, what: &str, t: f64) {
        if let Some(p) = self.out.progress.as_mut() {
            p(what, t);
        }
    }

    /// An observer for an integration that is not recorded (a reference
    /// or pilot run): it only reports its progress as `what`.
    pub fn observer<const N: usize>(
        &mut self,
        what: &'static str,
    ) -> impl FnMut(f64, &[f64; N]) -> Result<(), SimError> + '_ {
        move |t, _| {
            self.tick(what, t);
            Ok(())
        }
    }

    /// Whether anything is recorded at all.
    pub fn active(&self) -> bool {
        self.out.stream.is_some() || self.out.store || self.out.progress.is_some()
    }

    /// The stored rows, when the trajectory is kept.
    pub(crate) fn take_rows(&mut self) -> Option<Vec<Vec<f64>>> {
        self.out.store.then(|| std::mem::take(&mut self.rows))
    }
}

/// Checks the budget of stored output before a fixed-step run of
/// `t_end / h` steps with rows of `row_len` numbers.
pub(crate) fn check_budget(
    out: &Output<'_>,
    step: Option<Step>,
    t_end: f64,
    row_len: usize,
) -> Result<(), SimError> {
    if !out.store {
        return Ok(());
    }
    let rows = match step {
        Some(Step::Fixed(h)) => crate::fixed_step_count(t_end, h) + 1,
        _ => 1,
    };
    let needed = rows.saturating_mul(row_bytes(row_len));
    if needed > out.memory_budget {
        return Err(SimError::MemoryBudget {
            needed,
            budget: out.memory_budget,
        });
    }
    Ok(())
}

/// Integrates `sys` from `y0` over `[0, t_end]`, recording the row
/// `row(t, y)` of every accepted step when output is asked for: the one
/// integrate-and-record block of every integrated model. Returns the state
/// at `t_end`, the counts and the wall time.
pub fn integrate_recorded<const N: usize, S: crate::System<N>>(
    sys: &S,
    (method, step): (Method, Step),
    y0: [f64; N],
    t_end: f64,
    rec: &mut Recorder<'_, '_>,
    row: impl Fn(f64, &[f64; N]) -> Vec<f64>,
) -> Result<([f64; N], Stats, f64), SimError> {
    let active = rec.active();
    let start = Instant::now();
    let (y, stats) = integrate(
        sys,
        method,
        step,
        0.0,
        y0,
        t_end,
        Limits::default(),
        |t, y| {
            if active {
                rec.record(row(t, y))?;
            }
            Ok(())
        },
    )
    .map_err(|e| {
        e.in_run(|| {
            let step = match step {
                Step::Fixed(h) => format!("dt={h:e}"),
                Step::Tolerance(t) => format!("tol={t:e}"),
            };
            format!("the run ({method}, {step})")
        })
    })?;
    Ok((y, stats, start.elapsed().as_secs_f64()))
}

/// A row `[t, y…]`.
pub fn time_and_state<const N: usize>(t: f64, y: &[f64; N]) -> Vec<f64> {
    let mut row = Vec::with_capacity(N + 1);
    row.push(t);
    row.extend_from_slice(y);
    row
}

/// Runs `f` once, and again until `min_time` seconds are spent when one
/// run is shorter: its result and the mean wall time of one run.
pub fn timed<T>(
    min_time: f64,
    mut f: impl FnMut() -> Result<T, SimError>,
) -> Result<(T, f64), SimError> {
    let start = Instant::now();
    let mut out = f()?;
    let first = start.elapsed().as_secs_f64();
    if first >= min_time {
        return Ok((out, first));
    }
    let reps = ((min_time / first.max(1e-7)).ceil() as u32).clamp(1, 1000);
    let start = Instant::now();
    for _ in 0..reps {
        out = f()?;
    }
    Ok((out, start.elapsed().as_secs_f64() / reps as f64))
}
