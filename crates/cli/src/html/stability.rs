//! `hdot stability --html`: the page of a sweep — its report (what was
//! swept, where the motion is stable) as a table and the chart of the
//! eigenvalues against the parameter, inline.

use hdot_sim::stability::StabilityScene;

use super::shell::{Shell, chart, report_table};

/// The page of a sweep of `scene`: `report` is the text report the
/// command prints, `svg` the chart it wrote.
pub fn stability_page(scene: &StabilityScene, report: &str, svg: &str) -> String {
    let mut s = String::from("<section class=\"report\">\n<h2>Report</h2>\n");
    s.push_str(&report_table(report));
    s.push_str("</section>\n<section class=\"charts\">\n<h2>Eigenvalues</h2>\n");
    s.push_str(&chart(
        svg,
        &format!(
            "Real and imaginary parts of the eigenvalues λ against {} (one line per eigenvalue).",
            scene.parameter
        ),
    ));
    s.push_str("</section>\n");
    Shell {
        title: &scene.name,
        command: "hdot stability",
        description: &scene.description,
        detail: format!(
            "{} · {} from {} to {}, {} values",
            scene.file.display(),
            scene.parameter,
            scene.from,
            scene.to,
            scene.count
        ),
    }
    .page(&s, "")
}
