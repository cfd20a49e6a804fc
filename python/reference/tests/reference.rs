//! The reference program itself: its numbers read back bit for bit equal to the library's, known
//! answers come out (the uniform state and the kink cost nothing), and errors carry the library's
//! message. (Building this test is also what builds the program for `cargo xtask test`.)

use std::io::Write;
use std::process::{Command, Stdio};

use rotor_chain::Potential;
use rotor_chain::RuntimeChain;
use serde_json::{Value, json};

fn reference(cases: &Value) -> Vec<Value> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rotor-chain-reference"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    child.stdin.take().unwrap().write_all(cases.to_string().as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    serde_json::from_slice::<Value>(&out.stdout).unwrap().as_array().unwrap().clone()
}

#[test]
fn numbers_round_trip_exactly_and_known_answers_hold() {
    let theta: Vec<f64> = (0..30).map(|i| 0.4 * (0.7 * i as f64).sin() + 1.0 / 3.0).collect();
    let chain = json!({"n": 30, "r": 0.8, "k": 1e4, "theta_bar": 0.45});
    let results = reference(&json!([
        {"chain": chain, "op": "evaluate", "theta": theta},
        {"chain": chain, "op": "evaluate", "theta": vec![0.45; 30]},
        {"chain": chain, "op": "kink", "centre": 14.5},
        {"chain": {"n": 30, "r": 0.8, "k": 1e4, "theta_bar": 0.7}, "op": "build"},
        {"chain": {"n": 30, "r": 0.8, "k": "nan", "theta_bar": 0.3}, "op": "build"},
    ]));
    let model = RuntimeChain::builder(30, 0.8, 1e4, 0.45).build().unwrap();
    let energy = results[0]["ok"]["energy"].as_f64().unwrap();
    assert_eq!(energy.to_bits(), model.energy(&theta).to_bits());
    let mut gradient = vec![0.0; 30];
    model.gradient_into(&theta, &mut gradient);
    let got: Vec<f64> =
        results[0]["ok"]["gradient"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    assert_eq!(got, gradient);
    // The uniform state is a zero-energy equilibrium.
    assert!(results[1]["ok"]["energy"].as_f64().unwrap().abs() < 1e-20);
    assert!(
        results[1]["ok"]["gradient"].as_array().unwrap().iter().all(|g| g.as_f64().unwrap().abs() < 1e-9)
    );
    // The kink costs no energy.
    let kink: Vec<f64> =
        results[2]["ok"]["theta"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    assert!(model.energy(&kink) < 1e-20);
    let error = RuntimeChain::builder(30, 0.8, 1e4, 0.7).build().unwrap_err().to_string();
    assert_eq!(results[3]["error"].as_str(), Some(error.as_str()));
    assert!(results[4]["error"].as_str().unwrap().contains("`k` must be a finite number > 0, got NaN"));
}
