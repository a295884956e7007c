#pragma once
/// \file Gauss–Newton normal equations H = JᵀWJ, g = JᵀWr over the active parameters,
/// accumulated from sparse residual rows.
///
/// Rows are buffered into a dense block (columns = active parameters) and folded into H with a
/// symmetric rank-k update (Eigen's blocked SYRK): per-row scatter of nnz² products is what made
/// assembly dominate the registration time before.
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "breastfit/core/types.h"

namespace breastfit::fit {

class NormalEquations {
 public:
  explicit NormalEquations(int num_params = 0);
  /// Resizes for num_params parameters, all active.
  void resize(int num_params);
  /// Only these parameters (indices into the full vector) get rows and columns; the others are
  /// ignored by add_row. H and g are then in the order of `active`.
  void set_active(const std::vector<int>& active);
  /// Zeroes H, g and the cost.
  void clear();
  /// In gradient-only mode add_row accumulates g and the cost but not H (which keeps its last
  /// value): a solver may reuse a Hessian for a few iterations at the price of one gradient.
  void set_gradient_only(bool on) { gradient_only_ = on; }
  /// Number of active parameters (size of H and g).
  int size() const { return static_cast<int>(active_.size()); }
  const std::vector<int>& active() const { return active_; }
  /// Whether any parameter of the full range [begin, end) is active (a term may leave out the
  /// Jacobian entries of a range no row keeps).
  bool any_active(int begin, int end) const;

  /// Adds weight · (r + Σ_k val_k δ_{idx_k})² : H += w vvᵀ, g += w r v, cost += w r².
  /// idx are full parameter indices; entries of inactive parameters are dropped.
  void add_row(const int* idx, const double* val, int nnz, double r, double weight);
  /// A row assembled from parts (e.g. the corners of a triangle, weighted by barycentrics):
  /// begin_row(r, w), any number of add_to_row(idx, val, nnz, scale) adding scale·val to the
  /// row's coefficients (indices may repeat across parts), then end_row().
  void begin_row(double r, double weight);
  void add_to_row(const int* idx, const double* val, int nnz, double scale);
  void end_row();
  /// Folds buffered rows into H and mirrors the upper triangle. Call once after all rows.
  void finalize();

  /// The k-th partial of these equations: the same active parameters and mode, emptied, to take
  /// the rows of one chunk on another thread (fit/chunked_assembly.h). Kept between calls (no
  /// allocation per iteration); not thread-safe: take every partial before the threads start.
  NormalEquations& partial(int k);
  /// Adds a partial's rows: its H (upper triangle), g and cost.
  void add_partial(NormalEquations& p);

  /// Valid after finalize().
  const Eigen::MatrixXd& H() const { return H_; }
  const Eigen::VectorXd& g() const { return g_; }
  double cost() const { return cost_; }

 private:
  void flush();

  static constexpr int kBlockRows = 64;
  std::vector<int> active_;      // active → full index
  std::vector<int> column_;      // full index → active column, or −1
  Eigen::MatrixXd H_;
  Eigen::VectorXd g_;
  Eigen::MatrixXd block_;        // kBlockRows × size(), rows scaled by sqrt(w)
  Eigen::VectorXd block_r_;      // sqrt(w)·r per buffered row
  int buffered_ = 0;
  double cost_ = 0.0;
  bool gradient_only_ = false;
  double row_r_ = 0.0, row_w_ = 0.0;  // the row being assembled by begin_row/add_to_row
  bool row_any_ = false;
  std::vector<std::unique_ptr<NormalEquations>> partials_;
};

}  // namespace breastfit::fit
