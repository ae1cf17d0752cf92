//! Bad input: a typed error naming what and where, never a panic.

use std::path::Path;

use hdot_num::{Body, BodyError, CsvErrorKind, ParticleCloud, Pose, Primitive};
use nalgebra::Vector3;

#[test]
fn csv_errors_name_file_line_and_field() {
    // table: text => (line, field, kind)
    let cases: &[(&str, usize, &str, CsvErrorKind)] = &[
        ("0,0,0,1\n1,2,3\n", 2, "m", CsvErrorKind::Missing),
        (
            "x,y,z,m\n0,0,0,-1\n",
            2,
            "m",
            CsvErrorKind::NonPositiveMass(-1.0),
        ),
        ("0,0,0,0\n", 1, "m", CsvErrorKind::NonPositiveMass(0.0)),
        // A subnormal mass: m x underflows, the centre would read 0.
        (
            "0,0,0,1e-320\n1e-10,0,0,1e-320\n",
            1,
            "m",
            CsvErrorKind::TinyMass(1e-320),
        ),
        (
            "# c\n\n0,NaN,0,1\n",
            3,
            "y",
            CsvErrorKind::NotFinite(f64::NAN),
        ),
        (
            "0,0,inf,1\n",
            1,
            "z",
            CsvErrorKind::NotFinite(f64::INFINITY),
        ),
        ("0,0,0,1,5\n", 1, "-", CsvErrorKind::TooMany(5)),
        (
            "0,zero,0,1\n",
            1,
            "y",
            CsvErrorKind::NotANumber("zero".into()),
        ),
        ("x,y,z,m\n# nothing\n", 0, "-", CsvErrorKind::Empty),
    ];
    for (text, line, field, kind) in cases {
        let e = ParticleCloud::from_csv_str(Path::new("p.csv"), text).unwrap_err();
        assert_eq!((e.line, e.field.as_str()), (*line, *field), "{text:?}: {e}");
        match (&e.kind, kind) {
            (CsvErrorKind::NotFinite(a), CsvErrorKind::NotFinite(b)) => {
                assert_eq!(a.is_nan(), b.is_nan())
            }
            (a, b) => assert_eq!(a, b),
        }
        assert!(e.to_string().starts_with(&format!(
            "{}: field `{field}`",
            hdot_num::error::at(Path::new("p.csv"), *line)
        )));
    }
    let e = ParticleCloud::from_csv_path(Path::new("/nonexistent/cloud.csv")).unwrap_err();
    assert!(matches!(e.kind, CsvErrorKind::Io(_)));
}

/// A CSV cloud that is not UTF-8 is an error at its line and column; a
/// cloud read is an input no output may replace (issue 21).
#[test]
fn a_csv_cloud_in_the_wrong_encoding_is_located_and_never_overwritten() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("latin1.csv");
    std::fs::write(&bad, b"x,y,z,m\n0,0,0,1 # \xb5\n").unwrap();
    let e = ParticleCloud::from_csv_path(&bad).unwrap_err();
    assert_eq!(e.line, 2, "{e}");
    assert!(
        e.to_string().contains("column 11") && e.to_string().contains("not UTF-8"),
        "{e}"
    );

    let cloud = dir.path().join("cloud.csv");
    std::fs::write(&cloud, "0,0,0,1\n1,0,0,1\n").unwrap();
    ParticleCloud::from_csv_path(&cloud).unwrap();
    let e = hdot_num::fsio::write_atomic(&cloud, b"replaced").unwrap_err();
    assert!(hdot_num::fsio::is_input_refusal(&e), "{e}");
    assert_eq!(
        std::fs::read_to_string(&cloud).unwrap(),
        "0,0,0,1\n1,0,0,1\n"
    );
}

#[test]
fn bad_bodies_are_rejected() {
    let p = Pose::identity();
    assert!(matches!(
        Body::try_new(Primitive::Disk { radius: 1.0 }, 0.0, p),
        Err(BodyError::NonPositiveMass { .. })
    ));
    assert!(matches!(
        Body::try_new(Primitive::Disk { radius: -1.0 }, 1.0, p),
        Err(BodyError::BadDimension {
            field: "radius",
            ..
        })
    ));
    assert!(matches!(
        Body::try_new(Primitive::Rod { length: f64::NAN }, 1.0, p),
        Err(BodyError::NotFinite {
            field: "length",
            ..
        })
    ));
    assert!(matches!(
        Body::try_new(
            Primitive::HollowCylinder {
                inner: 2.0,
                outer: 1.0,
                length: 1.0
            },
            1.0,
            p
        ),
        Err(BodyError::BadDimension { field: "inner", .. })
    ));
    assert!(matches!(
        Body::try_new(
            Primitive::Sphere { radius: 1.0 },
            1.0,
            Pose::translation(Vector3::new(f64::INFINITY, 0.0, 0.0))
        ),
        Err(BodyError::NotFinite { field: "x", .. })
    ));
    assert!(matches!(
        ParticleCloud::try_from_particles(std::iter::empty()),
        Err(BodyError::Empty { .. })
    ));
    assert!(matches!(
        hdot_num::Composite::try_new(vec![]),
        Err(BodyError::Empty { .. })
    ));
}
