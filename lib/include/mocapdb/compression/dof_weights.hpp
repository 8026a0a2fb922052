#pragma once
// Weights that turn pose-vector errors into joint-position errors (issue #4: "truncation spends its
// error budget in centimetres, not radians").
//
// For a pose vector p and an approximation p', let X_d = w_d · p_d. If |X_d − X'_d| ≤ E for every d,
// then every joint of the skeleton is within E cm of its true position (before the projection a
// joint with fewer than three rotation channels applies, see eval/joint_error.hpp). Why:
//  - a joint j moves by at most |Δt| + Σ_a θ_a · L_a over the rotation joints a that are strict
//    ancestors of j (θ_a the angle between true and approximate local rotation, L_a the longest
//    bone path from a to any joint below it: rotating a vector of length ℓ by θ moves it ≤ ℓ θ, and
//    angle errors of a chain add by the triangle inequality on SO(3));
//  - |Δt| ≤ √3 max_i |Δt_i|; the exponential map is 1-Lipschitz onto rotation angle, so θ_a ≤ √3 max
//    |Δv_i| for an exp map, and ≤ (1 + √2) max |Δv_i| for the root's swing-twist (s_x, ψ, s_z);
//  - with K the largest number of such terms on any joint's chain, w_d = K · c_d · L_d (c_d = √3 or
//    1 + √2, L_d = 1 for translations) makes each term ≤ E / K.
// The weights are also what the Tucker truncation sees: a dof's share of the Frobenius error is its
// share of the joint-position error bound.
#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb::compression {

/// The weights w (D entries, all > 0) of the header comment for `skeleton`'s pose vector. A rotation
/// joint that moves nothing (no joint below it at distance > 0) gets the lever of 1 cm, so its values
/// stay bounded.
VecX position_error_weights(const Skeleton& skeleton);

}  // namespace mocapdb::compression
