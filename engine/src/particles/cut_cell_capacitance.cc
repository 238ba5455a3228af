// The capacitance matrix of the cut-cell velocity operator; see particles/cut_cell_capacitance.h.
#include "dlmfd/particles/cut_cell_capacitance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dlmfd {

void CutCellResponses::Hold(int s, std::vector<double> full) {
  Held held;
  const std::size_t n = full.size();
  std::vector<int> index;  // the scan's, freed unless kept (a wide response holds none)
  std::vector<double> value;
  held.local = CutCellLocalResponses::EntriesOf(full.data(), n, n / kLocalShare, index, value);
  if (held.local) {
    held.index.assign(index.begin(), index.end());  // to size: 12 bytes an entry
    held.value.assign(value.begin(), value.end());
  }
  held.full = std::move(full);
  held_.emplace(s, std::move(held));
}

bool CutCellResponses::Local(int s, const std::vector<int>** index,
                             const std::vector<double>** value) const {
  const Held& held = held_.at(s);
  *index = &held.index;
  *value = &held.value;
  return held.local;
}

int CutCellResponses::Update(const std::vector<int>& rows) {
  const std::size_t n = fast_.grid().NodeCount();
  std::vector<char> wanted(n, 0);
  for (const int s : rows) wanted[static_cast<std::size_t>(s)] = 1;
  for (auto it = held_.begin(); it != held_.end();) {
    if (wanted[static_cast<std::size_t>(it->first)] != 0) {
      ++it;
    } else {
      spare_.push_back(std::move(it->second.full));  // its Dirichlet nodes hold 0, as a new one's
      it = held_.erase(it);
    }
  }
  std::vector<int> missing;
  for (const int s : rows)
    if (held_.count(s) == 0) missing.push_back(s);
  auto take = [&] {
    if (spare_.empty()) return std::vector<double>(n, 0.0);
    std::vector<double> x = std::move(spare_.back());
    spare_.pop_back();
    return x;
  };
  std::vector<double> tu(n, 0.0), tv(n, 0.0);
  for (std::size_t j = 0; j < missing.size(); j += 2) {
    const bool pair = j + 1 < missing.size();
    std::vector<double> cu = take(), cv = take();
    tu[missing[j]] = 1.0;
    if (pair) tv[missing[j + 1]] = 1.0;
    fast_.SolvePair(tu.data(), cu.data(), tv.data(), cv.data());
    tu[missing[j]] = 0.0;
    Hold(missing[j], std::move(cu));
    if (pair) {
      tv[missing[j + 1]] = 0.0;
      Hold(missing[j + 1], std::move(cv));
    } else {
      spare_.push_back(std::move(cv));
    }
  }
  return static_cast<int>(missing.size());
}

void CutCellLocalResponses::Clear() {
  kept_ = false;
  start_ = {0};
  index_ = {};
  value_ = {};
}

bool CutCellLocalResponses::EntriesOf(const double* response, std::size_t nodes, std::size_t cap,
                                      std::vector<int>& index, std::vector<double>& value) {
  double largest = 0.0;
  for (std::size_t i = 0; i < nodes; ++i) largest = std::max(largest, std::abs(response[i]));
  const double drop = std::numeric_limits<double>::epsilon() * largest;
  index.clear();
  value.clear();
  for (std::size_t i = 0; i < nodes; ++i) {
    if (std::abs(response[i]) <= drop) continue;
    if (value.size() == cap) return false;
    index.push_back(static_cast<int>(i));
    value.push_back(response[i]);
  }
  return true;
}

bool CutCellLocalResponses::Add(const double* response) {
  if (!kept_) return false;
  std::vector<int> index;
  std::vector<double> value;
  if (!EntriesOf(response, nodes_, budget_ - value_.size(), index, value)) {
    Clear();
    return false;
  }
  return Append(index, value);
}

bool CutCellLocalResponses::Append(const std::vector<int>& index,
                                   const std::vector<double>& value) {
  if (!kept_) return false;
  if (value.size() > budget_ - value_.size()) {
    Clear();
    return false;
  }
  index_.insert(index_.end(), index.begin(), index.end());
  value_.insert(value_.end(), value.begin(), value.end());
  start_.push_back(value_.size());
  return true;
}

void CutCellLocalResponses::SubtractPair(const double* ys, const double* zs, double* u,
                                         double* v) const {
  for (std::size_t s = 0; s + 1 < start_.size(); ++s) {
    const double a = ys[s], b = zs[s];
    for (std::size_t e = start_[s]; e < start_[s + 1]; ++e) {
      const auto i = static_cast<std::size_t>(index_[e]);
      u[i] -= a * value_[e];
      v[i] -= b * value_[e];
    }
  }
}

void CutCellLocalResponses::Subtract(const double* ys, double* u) const {
  for (std::size_t s = 0; s + 1 < start_.size(); ++s) {
    const double a = ys[s];
    for (std::size_t e = start_[s]; e < start_[s + 1]; ++e)
      u[static_cast<std::size_t>(index_[e])] -= a * value_[e];
  }
}

CutCellCapacitance::CutCellCapacitance(const SeparableHelmholtz& fast,
                                       const Eigen::SparseMatrix<double>& difference, double drop,
                                       CutCellResponses* responses)
    : fast_(fast),
      local_(static_cast<std::size_t>(difference.rows())) {
  const Eigen::Index n = difference.rows();
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = difference;
  double largest = 0.0;
  for (Eigen::Index k = 0; k < rows.nonZeros(); ++k)
    largest = std::max(largest, std::abs(rows.valuePtr()[k]));
  std::vector<Eigen::Triplet<double>> c;
  for (Eigen::Index i = 0; i < n; ++i) {
    bool kept = false;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, i); it; ++it) {
      if (std::abs(it.value()) <= drop * largest) continue;
      c.emplace_back(static_cast<int>(rows_.size()), static_cast<int>(it.col()), it.value());
      kept = true;
    }
    if (kept) rows_.push_back(static_cast<int>(i));
  }
  const auto k = static_cast<Eigen::Index>(rows_.size());
  coupling_.resize(k, n);
  coupling_.setFromTriplets(c.begin(), c.end());
  const auto size = static_cast<std::size_t>(n);
  // The Dirichlet nodes lie on the sides: the perimeter's nodes, each once.
  const Grid& grid = fast.grid();
  for (int j = 0; j <= grid.ny; ++j)
    for (int i = 0; i <= grid.nx; i += (j == 0 || j == grid.ny || grid.nx == 0) ? 1 : grid.nx)
      if (!fast.topology().IsUnknown(grid, i, j))
        dirichlet_.push_back(static_cast<int>(grid.Index(i, j)));
  zero_.assign(size, 0.0);
  tu_.assign(size, 0.0);
  tv_.assign(size, 0.0);
  cu_.assign(size, 0.0);
  cv_.assign(size, 0.0);
  y_.resize(k, 2);
  // The columns I + C A_0^-1 e_s: held by the responses, or solved for two at a time.
  Eigen::MatrixXd capacitance = Eigen::MatrixXd::Identity(k, k);
  if (responses != nullptr) {
    set_up_solves_ = responses->Update(rows_);
    for (Eigen::Index j = 0; j < k; ++j) {
      const std::vector<double>& r = responses->Of(rows_[j]);
      capacitance.col(j) += coupling_ * Eigen::Map<const Eigen::VectorXd>(r.data(), n);
    }
    // Their entries were found when they were made (CutCellResponses); a response without them
    // (more than n / kLocalShare) or a sum over the budget keeps the fast solve.
    for (Eigen::Index j = 0; j < k && local_.Kept(); ++j) {
      const std::vector<int>* index = nullptr;
      const std::vector<double>* value = nullptr;
      if (!responses->Local(rows_[j], &index, &value)) {
        local_.Clear();
      } else {
        local_.Append(*index, *value);
      }
    }
  }
  for (Eigen::Index j = 0; responses == nullptr && j < k; j += 2) {
    const bool pair = j + 1 < k;
    tu_[rows_[j]] = 1.0;
    if (pair) tv_[rows_[j + 1]] = 1.0;
    std::fill(cu_.begin(), cu_.end(), 0.0);
    std::fill(cv_.begin(), cv_.end(), 0.0);
    fast_.SolvePair(tu_.data(), cu_.data(), pair ? tv_.data() : zero_.data(), cv_.data());
    capacitance.col(j) += coupling_ * Eigen::Map<const Eigen::VectorXd>(cu_.data(), n);
    local_.Add(cu_.data());
    if (pair) {
      capacitance.col(j + 1) += coupling_ * Eigen::Map<const Eigen::VectorXd>(cv_.data(), n);
      local_.Add(cv_.data());
    }
    tu_[rows_[j]] = 0.0;
    if (pair) tv_[rows_[j + 1]] = 0.0;
    set_up_solves_ += pair ? 2 : 1;
  }
  if (k > 0) capacitance_.compute(capacitance);
}

// The fast solver reads x at its Dirichlet nodes only and writes every other node: only those are
// zeroed (the data of the homogeneous extension), here and in its second solve (cu_, cv_ hold 0
// there from construction: the fast solver leaves them as they are).
void CutCellCapacitance::SolvePair(const double* fu, double* u, const double* fv, double* v) {
  const auto n = static_cast<Eigen::Index>(zero_.size());
  for (const int k : dirichlet_) u[k] = v[k] = 0.0;
  fast_.SolvePair(fu, u, fv, v);
  if (rows_.empty()) return;
  y_.col(0) = coupling_ * Eigen::Map<const Eigen::VectorXd>(u, n);
  y_.col(1) = coupling_ * Eigen::Map<const Eigen::VectorXd>(v, n);
  y_ = capacitance_.solve(y_);  // in place: P y, then the two triangular solves
  if (local_.Kept()) {
    local_.SubtractPair(y_.col(0).data(), y_.col(1).data(), u, v);
    return;
  }
  for (std::size_t s = 0; s < rows_.size(); ++s) {
    tu_[rows_[s]] = y_(static_cast<Eigen::Index>(s), 0);
    tv_[rows_[s]] = y_(static_cast<Eigen::Index>(s), 1);
  }
  fast_.SolvePair(tu_.data(), cu_.data(), tv_.data(), cv_.data());
  for (Eigen::Index i = 0; i < n; ++i) {
    u[i] -= cu_[i];
    v[i] -= cv_[i];
  }
  for (const int s : rows_) tu_[s] = tv_[s] = 0.0;
}

void CutCellCapacitance::Solve(const double* f, double* x) {
  const auto n = static_cast<Eigen::Index>(zero_.size());
  for (const int k : dirichlet_) x[k] = 0.0;
  fast_.Solve(f, x);
  if (rows_.empty()) return;
  const Eigen::VectorXd y = capacitance_.solve(coupling_ * Eigen::Map<const Eigen::VectorXd>(x, n));
  if (local_.Kept()) {
    local_.Subtract(y.data(), x);
    return;
  }
  for (std::size_t s = 0; s < rows_.size(); ++s) tu_[rows_[s]] = y[static_cast<Eigen::Index>(s)];
  fast_.Solve(tu_.data(), cu_.data());
  for (Eigen::Index i = 0; i < n; ++i) x[i] -= cu_[i];
  for (const int s : rows_) tu_[s] = 0.0;
}

}  // namespace dlmfd
