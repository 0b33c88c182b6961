//! Rigid transforms and the contract pose form.
