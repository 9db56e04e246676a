//! Regression (a fuzz finding of issue 28's long run): `analyze` in floats, which unlike
//! `solve` runs in the scene's own units, on a contact whose normal is [0, 10³⁰⁸, 2]. Its
//! squared length is beyond f64: on the wrench route (more than 24 contacts) a verdict read
//! "contact A4 is not approaching (v_4x⁰ = NaN ≤ 0, eq. 74)" with status 0; on the dense route
//! G came out "not positive semidefinite" (status 3). The normal is a direction, and exactly
//! the scene is fine (`analyze --exact` answers). Now an axis or an inertance beyond f64 is
//! refused at once, naming the number (status 2), as every other float result beyond range.

use std::path::PathBuf;

use inertance::scalar::Exact;
use inertance::scene::Scene;
use inertance::scene::pipeline::RunError;
use inertance::tools::analyze::analyze_scene;

fn finding() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz_corpus/analyze-normal-beyond-f64.toml")
}

fn refused_naming(scene: &Scene, key: &str) {
    match analyze_scene::<f64>(scene, None) {
        Err(RunError::Scene(e)) => {
            assert_eq!(e.key, key);
            assert_eq!(e.value.as_deref(), Some("1e308"));
            assert!(e.message.contains("--exact"), "{e}");
        }
        Err(e) => panic!("refused for another reason: {e}"),
        Ok(r) => panic!("analysed: {}", r.to_text()),
    }
}

#[test]
fn on_the_wrench_route_the_normal_is_named() {
    let scene = Scene::load(&finding()).unwrap();
    assert_eq!(scene.contacts.len(), 25);
    refused_naming(&scene, "contact[24].normal[1]");
    let exact = analyze_scene::<Exact>(&scene, None).expect("exact answers");
    assert!(!exact.to_text().contains("NaN"));
}

#[test]
fn on_the_dense_route_the_normal_is_named() {
    let text = "[body]\nmass = 1.2\ninertia = [1.7, 1.7, 3.2]\nvelocity = [-1, -2, 0.8]\n\
                angular_velocity = [-1, \"-1/4\", 1.2]\n[[contact]]\npoint = [-5, 7, -2]\n\
                normal = [0, 2, 1]\nk = 0\n[[contact]]\npoint = [4, -6, -2]\n\
                normal = [0, 1e308, 2]\nk = 0.9\n";
    let scene = Scene::parse(text, "two.toml").unwrap();
    refused_naming(&scene, "contact[1].normal[1]");
    assert!(analyze_scene::<Exact>(&scene, None).is_ok());
}
