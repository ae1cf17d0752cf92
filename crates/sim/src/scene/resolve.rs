//! Where a derived scene's derivation is: a path from the scene's folder,
//! or a bare name found in a `derivations` folder at or above it.

use std::path::{Path, PathBuf};

/// Finds a derivation a scene names: `Ok((shown path, text))`.
pub type Resolve<'a> = &'a dyn Fn(&str) -> Result<(PathBuf, String), String>;

/// The default resolver: a `file` with a `/` or ending in `.toml` is a path
/// from the scene's folder; a bare name is `derivations/NAME.toml` in the
/// scene's folder or any folder above it — above it on disk, not only
/// in the path as given (`scene.toml` run in its own folder looks in the
/// folders above the working directory too).
pub fn resolve_near(scene: &Path, name: &str) -> Result<(PathBuf, String), String> {
    let dir = scene.parent().unwrap_or(Path::new("."));
    let candidates: Vec<PathBuf> = if name.contains('/') || name.ends_with(".toml") {
        vec![dir.join(name)]
    } else {
        // The folders of the path as given first (shown as written), then
        // those above it once made absolute.
        let absolute = std::env::current_dir()
            .map(|cwd| cwd.join(dir))
            .unwrap_or_else(|_| dir.to_path_buf());
        dir.ancestors()
            .chain(absolute.ancestors())
            .map(|a| a.join("derivations").join(format!("{name}.toml")))
            .collect()
    };
    for c in &candidates {
        if c.is_file() {
            let text = hdot_sym::textfile::read(c).map_err(|e| e.to_string())?;
            return Ok((c.clone(), text));
        }
    }
    Err(if name.contains('/') || name.ends_with(".toml") {
        format!("no derivation file {}", dir.join(name).display())
    } else {
        format!("no derivation `{name}` in a `derivations` folder at or above the scene's folder")
    })
}
