//! Presentation is exact: every presented component of every bundled
//! derivation (and of chain-3) expands back to the step's canonical value,
//! once the folded abbreviations are replaced by their definitions. The JSON
//! output relies on it (its `canonical` field is the value itself when a
//! step folds nothing).

use hdot_sym::derivation::{Derivation, load};
use hdot_sym::poly::Poly;

fn assert_exact(d: &Derivation) -> usize {
    let mut compared = 0;
    for s in &d.steps {
        let values = s.values();
        let presented = s.presented();
        assert_eq!(values.len(), presented.len(), "{}: {}", d.name, s.name);
        for (value, (c, e)) in values.into_iter().zip(&presented) {
            // An abbreviation's derivatives were folded too (ω̇_z): each
            // becomes the matching derivative of the definition.
            let expanded: Poly = e.to_poly().subst(&mut |a| {
                s.presentation
                    .fold
                    .iter()
                    .find(|(name, _)| a.base() == name.base() && a.order() >= name.order())
                    .map(|(name, def)| def.dt_n(a.order() - name.order()))
            });
            assert_eq!(
                &expanded, value,
                "{}: step {} component {c:?} does not expand back",
                d.name, s.name
            );
            compared += 1;
        }
    }
    compared
}

#[test]
fn every_presented_component_expands_to_its_value() {
    let dir = hdot_tests::repo_root().join("derivations");
    let mut compared = 0;
    let mut files = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml")
            && path.file_name().unwrap() != hdot_sym::course::MANIFEST_FILE
        {
            compared += assert_exact(&load(&path).unwrap());
            files += 1;
        }
    }
    compared += assert_exact(&hdot_sym::chain::derivation(3).unwrap());
    assert!(files >= 16, "only {files} derivation files");
    assert!(compared > 100, "only {compared} components compared");
}
