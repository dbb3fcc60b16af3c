// Numerically sound observability and controllability analysis for the stiff
// birotor model (entries from 1 to 2e5): the system is first balanced by a
// diagonal similarity (Osborne/Parlett-Reinsch) and time-scaled by its
// spectral radius, then the unobservable subspace is found with the
// orthogonal staircase recursion
//   N_0 = ker C,  N_{k+1} = { x in N_k : A x in N_k },
// using SVDs only. A plain rank of [C; CA; ...; CA^{n-1}] in double precision
// is wrong for this system; its singular values are still reported (scaled).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace birotor {

struct SubspaceReport {
  int state_size = 0;
  int rank = 0;                            // observable (controllable) dimension
  std::vector<std::string> hidden_states;  // state axes lying in the unobservable
                                           // (uncontrollable) subspace
  Eigen::MatrixXd hidden_basis;            // orthonormal basis of that subspace,
                                           // original coordinates (n x (n - rank))
  Eigen::VectorXd singular_values;         // of the balanced, time-scaled
                                           // observability (controllability) matrix
  Eigen::VectorXd pbh_margins;             // min singular value of [A - lambda I; C]
                                           // per eigenvalue (PBH test), scaled
  double time_scale_s = 1;                 // 1 / spectral radius used for scaling
};

// Observability of (A, C). state_names names the columns of A.
SubspaceReport AnalyzeObservability(const Eigen::MatrixXd& a, const Eigen::MatrixXd& c,
                                    const std::vector<std::string>& state_names);

// Controllability of (A, B), by duality with (A^T, B^T).
SubspaceReport AnalyzeControllability(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                      const std::vector<std::string>& state_names);

// Rows of C that measure the named states (names from state_names).
// Returns false and fills unknown if a name is not a state.
bool SelectionMatrix(const std::vector<std::string>& state_names, const std::vector<std::string>& measured,
                     Eigen::MatrixXd* c, std::string* unknown);

}  // namespace birotor
