#include "breastfit/fit/normal_equations.h"

#include <cmath>
#include <numeric>

namespace breastfit::fit {

NormalEquations::NormalEquations(int num_params) { resize(num_params); }

void NormalEquations::resize(int num_params) {
  std::vector<int> all(num_params);
  std::iota(all.begin(), all.end(), 0);
  column_.assign(num_params, -1);
  set_active(all);
}

void NormalEquations::set_active(const std::vector<int>& active) {
  int max_index = -1;
  for (int i : active) max_index = std::max(max_index, i);
  if (static_cast<int>(column_.size()) <= max_index) column_.resize(max_index + 1, -1);
  std::fill(column_.begin(), column_.end(), -1);
  active_ = active;
  for (size_t c = 0; c < active_.size(); ++c) column_[active_[c]] = static_cast<int>(c);
  const int n = size();
  H_.setZero(n, n);
  g_.setZero(n);
  block_.setZero(kBlockRows, n);
  block_r_.setZero(kBlockRows);
  buffered_ = 0;
  cost_ = 0.0;
}

void NormalEquations::clear() {
  H_.setZero();
  g_.setZero();
  block_.setZero();
  block_r_.setZero();
  buffered_ = 0;
  cost_ = 0.0;
}

void NormalEquations::add_row(const int* idx, const double* val, int nnz, double r, double w) {
  cost_ += w * r * r;
  if (w <= 0.0) return;
  const double s = std::sqrt(w);
  const int row = buffered_;
  bool any = false;
  for (int k = 0; k < nnz; ++k) {
    const int c = idx[k] < static_cast<int>(column_.size()) ? column_[idx[k]] : -1;
    if (c < 0) continue;
    block_(row, c) += s * val[k];
    any = true;
  }
  if (!any) return;
  block_r_[row] = s * r;
  if (++buffered_ == kBlockRows) flush();
}

void NormalEquations::flush() {
  if (buffered_ == 0) return;
  const auto B = block_.topRows(buffered_);
  H_.selfadjointView<Eigen::Upper>().rankUpdate(B.transpose());
  g_.noalias() += B.transpose() * block_r_.head(buffered_);
  block_.topRows(buffered_).setZero();
  block_r_.head(buffered_).setZero();
  buffered_ = 0;
}

void NormalEquations::finalize() {
  flush();
  H_.triangularView<Eigen::StrictlyLower>() = H_.transpose().triangularView<Eigen::StrictlyLower>();
}

}  // namespace breastfit::fit
