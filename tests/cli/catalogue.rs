//! The one catalogue of derived quantities, seen from a scene: a claim that names a quantity
//! pulls in the stage that derives it, whatever the scene's outputs.

use super::{mechbook, scratch, stderr, stdout};

#[test]
fn a_claim_on_twice_energy_alone_gets_it_derived() {
    let dir = scratch("twice-energy");
    // No outputs: the claims alone must pull in Poinsot's stage. Before the catalogue,
    // `twice_energy` had no stage, so it was never derived and the claim read as an erratum.
    let scene = r#"
id = "energy"
title = "Twice the kinetic energy"
notes = { lecture = "3/9", equations = ["77"] }
symbols = { I1 = "moment 1", I2 = "moment 2", I3 = "moment 3", w1 = "rate 1", w2 = "rate 2", w3 = "rate 3", L1 = "momentum 1", L2 = "momentum 2", L3 = "momentum 3" }

[outputs]
want = []

[[claim]]
eq = "77"
statement = "twice the kinetic energy"
quantity = "twice_energy"
value = "I1*w1^2 + I2*w2^2 + I3*w3^2"
expect = "agrees"

[[claim]]
eq = "77a"
statement = "the square of the angular momentum"
quantity = "momentum_squared"
value = "(I1*w1)^2 + (I2*w2)^2 + (I3*w3)^2"
expect = "agrees"
"#;
    std::fs::write(dir.join("energy.toml"), scene).unwrap();
    let out = mechbook(&["check", "--json", dir.join("energy.toml").to_str().unwrap()]);
    let json: serde_json::Value = serde_json::from_str(&stdout(&out))
        .unwrap_or_else(|e| panic!("{e}: {}\n{}", stdout(&out), stderr(&out)));
    let claims = json["scenes"][0]["claims"].as_array().unwrap();
    assert_eq!(claims.len(), 2, "{json}");
    for c in claims {
        assert_eq!(c["verdict"], "agrees", "{c}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
