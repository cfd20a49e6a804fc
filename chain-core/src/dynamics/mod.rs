//! Dynamics of the chain (paper Secs. V, VI, VII-B and Appendix B): `M r_i^2 thetadd_i = -dV/dtheta_i`,
//! generic over [`crate::ChainModel`].
