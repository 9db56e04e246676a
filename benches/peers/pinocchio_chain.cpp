// Pinocchio's impulseDynamics on the articulated chains of chains.py, timed in C++, with no
// Python between the clock and the call.
//
// Built and run by chains.py (the build is pin_build.py's, shared with compare.py's
// pinocchio_call.cpp: g++ against the headers and libraries of the `pin` wheel's cmeel prefix and
// Eigen's `cmeel-eigen` headers).  The model is chains.py's own, not rebuilt here: Python writes
// it with `model.saveToBinary(path)` (Boost binary archive, every double bit for bit) and this
// program reads it with `Model::loadFromBinary`.  Reads chains from standard input:
//
//   COUNT
//   MODEL_PATH                                  (one line: the model's binary archive)
//   ROWS E
//   q (nq numbers)  v (nv numbers)  J (ROWS x nv numbers, row by row)
//   ... (COUNT times)
//
// q, v and J are chains.py's (J: the contacts' normal rows of the frame Jacobians, taken in
// Python outside the timing), written with repr (shortest round-trip) so they are the same
// doubles.  Then the bare call impulseDynamics(model, data, q, v, J, e, 0) — crba + Cholesky of M
// and of J M^-1 J^T + solve — is timed as pinocchio_call.cpp does: the median over 7 runs of the
// mean time per call, each run at least 20 ms.
//
// Prints one JSON object per chain:
//   {"links": N, "ns_per_call": t, "dq_after": [...], "impulse": [...]}
// (N = model.njoints - 1; Pinocchio's dq_after and impulse_c, whose sign is minus inertance's P).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <pinocchio/algorithm/contact-dynamics.hpp>
#include <pinocchio/multibody.hpp>
#include <pinocchio/serialization.hpp>

namespace pin = pinocchio;

static void print_vec(const char * key, const Eigen::VectorXd & x) {
  std::printf(", \"%s\": [", key);
  for (Eigen::Index i = 0; i < x.size(); ++i) std::printf("%s%.17g", i ? ", " : "", x[i]);
  std::printf("]");
}

int main() {
  int count = 0;
  if (!(std::cin >> count)) return 2;
  for (int c = 0; c < count; ++c) {
    std::string path;
    std::cin >> std::ws;
    std::getline(std::cin, path);
    int rows = 0;
    double e = 0.0;
    std::cin >> rows >> e;
    if (!std::cin || rows < 1) return 2;

    pin::Model model;
    model.loadFromBinary(path);
    Eigen::VectorXd q(model.nq), v(model.nv);
    Eigen::MatrixXd J(rows, model.nv);
    for (Eigen::Index i = 0; i < q.size(); ++i) std::cin >> q[i];
    for (Eigen::Index i = 0; i < v.size(); ++i) std::cin >> v[i];
    for (int r = 0; r < rows; ++r)
      for (Eigen::Index i = 0; i < J.cols(); ++i) std::cin >> J(r, i);
    if (!std::cin) return 2;

    pin::Data data(model);
    pin::impulseDynamics(model, data, q, v, J, e, 0.0);  // warm-up, and the result
    Eigen::VectorXd dq_after = data.dq_after, impulse = data.impulse_c;

    using clock = std::chrono::steady_clock;
    long reps = 1;
    for (;;) {  // reps per run: at least 20 ms
      auto t0 = clock::now();
      for (long k = 0; k < reps; ++k) pin::impulseDynamics(model, data, q, v, J, e, 0.0);
      double dt = std::chrono::duration<double>(clock::now() - t0).count();
      if (dt >= 0.02) break;
      reps *= 2;
    }
    std::vector<double> runs;
    for (int run = 0; run < 7; ++run) {
      auto t0 = clock::now();
      for (long k = 0; k < reps; ++k) pin::impulseDynamics(model, data, q, v, J, e, 0.0);
      runs.push_back(std::chrono::duration<double, std::nano>(clock::now() - t0).count() / reps);
    }
    std::sort(runs.begin(), runs.end());

    std::printf("{\"links\": %d, \"ns_per_call\": %.6g", model.njoints - 1, runs[3]);
    print_vec("dq_after", dq_after);
    print_vec("impulse", impulse);
    std::printf("}\n");
    std::fflush(stdout);
  }
  return 0;
}
