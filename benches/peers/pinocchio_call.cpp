// Pinocchio's impulseDynamics timed in C++, with no Python between the clock and the call.
//
// Built and run by compare.py (see README.md there) against the headers and libraries of the
// `pin` wheel (cmeel prefix) and Eigen (`cmeel-eigen`).  Reads scenes from standard input:
//
//   COUNT
//   m J1 J2 J3  vx vy vz  wx wy wz  e  N  (rx ry rz nx ny nz) x N      (one scene per line)
//
// a free body (free-flyer joint, CoM at the joint origin, principal axes = joint axes), velocity
// [v_C; omega] in body axes, N contacts at r_i with unit normals n_i, one restitution
// coefficient e (Newton's law, the only one impulseDynamics has).  The normal-only constraint
// Jacobian is taken from Pinocchio's own kinematics (computeJointJacobians + getFrameJacobian,
// LOCAL) once per scene, outside the timing, as compare.py's Python path does.  Then the bare
// call impulseDynamics(model, data, q, v_before, J, e, 0) — crba + Cholesky of J M^-1 J^T + solve —
// is timed: the median over 7 runs of the mean time per call, each run at least 20 ms.
//
// Prints one JSON object per scene: {"ns_per_call": ..., "impulse": [...], "v_after": [...]}
// (Pinocchio's impulse lambda = -P; v_after in Pinocchio's order [v; omega]).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <vector>

#include <pinocchio/algorithm/contact-dynamics.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/frames.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/joint-configuration.hpp>
#include <pinocchio/multibody.hpp>

namespace pin = pinocchio;

int main() {
  int count = 0;
  if (!(std::cin >> count)) return 2;
  for (int s = 0; s < count; ++s) {
    double m, e;
    Eigen::Vector3d J, vc, w;
    int n = 0;
    std::cin >> m >> J[0] >> J[1] >> J[2] >> vc[0] >> vc[1] >> vc[2] >> w[0] >> w[1] >> w[2] >> e >> n;
    if (!std::cin || n < 1) return 2;
    std::vector<Eigen::Vector3d> r(n), nrm(n);
    for (int i = 0; i < n; ++i)
      std::cin >> r[i][0] >> r[i][1] >> r[i][2] >> nrm[i][0] >> nrm[i][1] >> nrm[i][2];
    if (!std::cin) return 2;

    pin::Model model;
    auto jid = model.addJoint(0, pin::JointModelFreeFlyer(), pin::SE3::Identity(), "body");
    model.appendBodyToJoint(jid, pin::Inertia(m, Eigen::Vector3d::Zero(), J.asDiagonal()),
                            pin::SE3::Identity());
    std::vector<pin::FrameIndex> frames;
    for (int i = 0; i < n; ++i)
      frames.push_back(model.addFrame(pin::Frame("A" + std::to_string(i + 1), jid,
                                                 pin::SE3(Eigen::Matrix3d::Identity(), r[i]),
                                                 pin::FrameType::OP_FRAME)));
    pin::Data data(model);
    Eigen::VectorXd q = pin::neutral(model);
    Eigen::VectorXd v0(6);
    v0 << vc, w;

    pin::computeJointJacobians(model, data, q);
    Eigen::MatrixXd Jn(n, model.nv);
    for (int i = 0; i < n; ++i) {
      pin::Data::Matrix6x Jf(6, model.nv);
      Jf.setZero();
      pin::getFrameJacobian(model, data, frames[i], pin::LOCAL, Jf);
      Jn.row(i) = nrm[i].transpose() * Jf.topRows<3>();
    }

    pin::impulseDynamics(model, data, q, v0, Jn, e, 0.0);  // warm-up, and the result
    Eigen::VectorXd impulse = data.impulse_c, v_after = data.dq_after;

    using clock = std::chrono::steady_clock;
    long reps = 1;
    for (;;) {  // reps per run: at least 20 ms
      auto t0 = clock::now();
      for (long k = 0; k < reps; ++k) pin::impulseDynamics(model, data, q, v0, Jn, e, 0.0);
      double dt = std::chrono::duration<double>(clock::now() - t0).count();
      if (dt >= 0.02) break;
      reps *= 2;
    }
    std::vector<double> runs;
    for (int run = 0; run < 7; ++run) {
      auto t0 = clock::now();
      for (long k = 0; k < reps; ++k) pin::impulseDynamics(model, data, q, v0, Jn, e, 0.0);
      runs.push_back(std::chrono::duration<double, std::nano>(clock::now() - t0).count() / reps);
    }
    std::sort(runs.begin(), runs.end());

    std::printf("{\"ns_per_call\": %.6g, \"impulse\": [", runs[3]);
    for (int i = 0; i < n; ++i) std::printf("%s%.17g", i ? ", " : "", impulse[i]);
    std::printf("], \"v_after\": [");
    for (int i = 0; i < 6; ++i) std::printf("%s%.17g", i ? ", " : "", v_after[i]);
    std::printf("]}\n");
  }
  return 0;
}
