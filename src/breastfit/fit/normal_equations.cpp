#include "breastfit/fit/normal_equations.h"

#include <algorithm>
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

bool NormalEquations::any_active(int begin, int end) const {
  for (int i = std::max(begin, 0); i < std::min(end, static_cast<int>(column_.size())); ++i)
    if (column_[i] >= 0) return true;
  return false;
}

void NormalEquations::clear() {
  if (!gradient_only_) H_.setZero();
  g_.setZero();
  block_.setZero();
  block_r_.setZero();
  buffered_ = 0;
  cost_ = 0.0;
}

void NormalEquations::add_row(const int* idx, const double* val, int nnz, double r, double w) {
  begin_row(r, w);
  add_to_row(idx, val, nnz, 1.0);
  end_row();
}

void NormalEquations::begin_row(double r, double w) {
  cost_ += w * r * r;
  row_r_ = r;
  row_w_ = w > 0.0 ? w : 0.0;
  row_any_ = false;
}

void NormalEquations::add_to_row(const int* idx, const double* val, int nnz, double scale) {
  if (row_w_ <= 0.0) return;
  const int ncol = static_cast<int>(column_.size());
  if (gradient_only_) {
    const double f = row_w_ * row_r_ * scale;
    for (int k = 0; k < nnz; ++k) {
      const int c = idx[k] < ncol ? column_[idx[k]] : -1;
      if (c >= 0) g_[c] += f * val[k];
    }
    return;
  }
  const double f = std::sqrt(row_w_) * scale;
  double* row = block_.data() + buffered_;  // column-major: element (buffered_, c) at row[c * kBlockRows]
  for (int k = 0; k < nnz; ++k) {
    const int c = idx[k] < ncol ? column_[idx[k]] : -1;
    if (c < 0) continue;
    row[static_cast<Eigen::Index>(c) * kBlockRows] += f * val[k];
    row_any_ = true;
  }
}

void NormalEquations::end_row() {
  if (gradient_only_ || !row_any_) return;
  block_r_[buffered_] = std::sqrt(row_w_) * row_r_;
  row_any_ = false;
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

NormalEquations& NormalEquations::partial(int k) {
  if (static_cast<int>(partials_.size()) <= k) partials_.resize(k + 1);
  auto& p = partials_[k];
  if (!p) p = std::make_unique<NormalEquations>();
  if (p->active_ != active_) p->set_active(active_);
  p->gradient_only_ = gradient_only_;
  p->clear();
  return *p;
}

void NormalEquations::add_partial(NormalEquations& p) {
  p.flush();
  if (!gradient_only_) H_.triangularView<Eigen::Upper>() += p.H_;
  g_ += p.g_;
  cost_ += p.cost_;
}

void NormalEquations::finalize() {
  if (gradient_only_) return;
  flush();
  H_.triangularView<Eigen::StrictlyLower>() = H_.transpose().triangularView<Eigen::StrictlyLower>();
}

}  // namespace breastfit::fit
