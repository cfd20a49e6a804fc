//! The macro reads only the fields its keys name: other fields, of any type, and tuple structs
//! are left alone, and derives on the struct still apply.
use rotor_chain::prelude::*;

/// A chain that carries its own bookkeeping beside the one field a key reads.
#[derive(Clone, Debug)]
#[rotor_chain(n = 6, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(2, k = k_imp))]
pub struct Labelled {
    pub label: String,
    pub runs: u32,
    pub k_imp: f64,
    pub notes: Vec<&'static str>,
}

/// A tuple struct: no key can name its fields, so every value is a literal.
#[rotor_chain(n = 6, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
pub struct Tuple(pub u8, pub String);

/// The sum of the gradient's entries through the trait, for any chain.
fn total_force(chain: &impl ChainModel, theta: &[f64]) -> f64 {
    let mut g = vec![0.0; theta.len()];
    chain.gradient_into(theta, &mut g);
    g.iter().sum()
}

pub fn main() {
    let chain = Labelled { label: "impurity run".into(), runs: 3, k_imp: 2.0e4, notes: vec!["soft"] };
    chain.check().expect("valid");
    let copy = chain.clone();
    assert_eq!((copy.label.as_str(), copy.runs, copy.notes.len()), ("impurity run", 3, 1));
    let theta = [0.58, 0.5, -0.3, 0.2, -0.58, 0.1];
    // The impurity field is read: doubling k_imp changes the energy.
    let soft = Labelled { k_imp: 1.0e4, ..chain.clone() };
    assert!(chain.energy(&theta) > soft.energy(&theta));
    let tuple = Tuple(7, "tuple".into());
    tuple.check().expect("valid");
    // Tuple has the same parameters as `soft`: the same energy and forces.
    assert_eq!(tuple.energy(&theta), soft.energy(&theta));
    assert_eq!(total_force(&tuple, &theta), total_force(&soft, &theta));
    assert_eq!((tuple.0, tuple.1.as_str()), (7, "tuple"));
}
