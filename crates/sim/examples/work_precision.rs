//! Same sweep as `hdot work-precision`, without the CLI (for regenerating the
//! bundled charts while the CLI crate is being changed):
//! `cargo run --release -p hdot-sim --example work_precision -- SCENE OUT_DIR`.

use std::io::Write;
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let scene_path = PathBuf::from(args.next().ok_or("usage: work_precision SCENE OUT_DIR")?);
    let out = PathBuf::from(args.next().unwrap_or_else(|| ".".into()));
    let scene = hdot_sim::scene::Scene::from_file(&scene_path)?;
    std::fs::create_dir_all(&out)?;
    let stem = out.join(format!(
        "{}-work-precision",
        scene_path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("scene")
    ));
    let rows =
        hdot_sim::run::work_precision(&scene, scene.t_end, 0.02, |r| eprintln!("{}", r.csv()))?;
    let mut f = std::fs::File::create(stem.with_extension("csv"))?;
    writeln!(f, "{}", hdot_sim::run::CSV_HEADER)?;
    for r in &rows {
        writeln!(f, "{}", r.csv())?;
    }
    hdot_sim::run::write_chart(
        &rows,
        &stem,
        &format!("{} (T = {})", scene.name, scene.t_end),
    )?;
    println!("wrote {}", stem.display());
    Ok(())
}
