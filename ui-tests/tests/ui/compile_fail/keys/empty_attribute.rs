use rotor_chain::prelude::*;

#[rotor_chain]
pub struct Chain;

fn main() {}
