#include "physics/patient/chain_mail.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <stdexcept>
#include <string>

namespace vesica::physics {

void ValidateChainMailParameters(const ChainMailParameters& p, const char* organ) {
  const auto bad = [&](const char* what) { throw std::invalid_argument(std::string(organ) + " ChainMail: " + what); };
  if (!(p.compression_gamma > 0.0 && p.compression_gamma <= 1.0)) bad("compression_gamma must be in (0, 1]");
  if (!(p.stretch_lambda >= 1.0 && std::isfinite(p.stretch_lambda))) bad("stretch_lambda must be >= 1");
  if (!(p.shear_mu >= 0.0 && std::isfinite(p.shear_mu))) bad("shear_mu must be >= 0");
}

ChainMail::ChainMail(int element_count, const ChainMailParameters& parameters)
    : parameters_(parameters), fixed_(static_cast<std::size_t>(element_count), 0) {
  ValidateChainMailParameters(parameters, "");
  first_.assign(static_cast<std::size_t>(element_count) + 1, 0);
}

void ChainMail::Link(int a, int b, const Eigen::Vector3d& step_m) {
  const int n = element_count();
  if (a == b || a < 0 || b < 0 || a >= n || b >= n) throw std::invalid_argument("ChainMail link between bad elements");
  if (step_m.isZero(0.0)) throw std::invalid_argument("ChainMail link with a zero rest step");
  links_.push_back({a, b, step_m});
  dirty_ = true;
}

void ChainMail::Fix(int element) { fixed_.at(static_cast<std::size_t>(element)) = 1; }

void ChainMail::Finalise() const {
  if (!dirty_) return;
  const std::size_t n = fixed_.size();
  std::vector<int> count(n + 1, 0);
  for (const LinkRecord& l : links_) {
    ++count[static_cast<std::size_t>(l.a) + 1];
    ++count[static_cast<std::size_t>(l.b) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) count[i + 1] += count[i];
  first_ = count;
  halves_.assign(links_.size() * 2, Half{});
  std::vector<int> fill(first_.begin(), first_.end() - 1);
  const ChainMailParameters& p = parameters_;
  for (const LinkRecord& l : links_) {
    const double length = l.step_m.norm();
    Half ab{l.b, {}, {}};
    for (int c = 0; c < 3; ++c) {
      const double s = l.step_m(c);
      if (s != 0.0) {  // compression and stretch of this coordinate's extent (eqs. 3-4, 5-6, 7-8)
        const double shrink = (p.compression_gamma - 1.0) * std::abs(s), grow = (p.stretch_lambda - 1.0) * std::abs(s);
        ab.lo[c] = static_cast<float>(s > 0 ? shrink : -grow);
        ab.hi[c] = static_cast<float>(s > 0 ? grow : -shrink);
      } else {  // shear across it
        ab.lo[c] = static_cast<float>(-p.shear_mu * length);
        ab.hi[c] = static_cast<float>(p.shear_mu * length);
      }
    }
    Half ba{l.a, {}, {}};
    for (int c = 0; c < 3; ++c) {
      ba.lo[c] = -ab.hi[c];
      ba.hi[c] = -ab.lo[c];
    }
    halves_[static_cast<std::size_t>(fill[static_cast<std::size_t>(l.a)]++)] = ab;
    halves_[static_cast<std::size_t>(fill[static_cast<std::size_t>(l.b)]++)] = ba;
  }
  pinned_scratch_.assign(n, 0);
  dirty_ = false;
}

int ChainMail::Pass(std::span<const int> seeds, int c, bool raise, std::span<Eigen::Vector3d> u,
                    std::span<const std::uint8_t> pinned, int& blocked) const {
  // Longest-path Dijkstra: the element with the largest displacement (raise) is settled first.
  // The heap is a member so that a move allocates nothing.
  std::vector<Entry>& heap = heap_;
  heap.clear();
  const double sign = raise ? 1.0 : -1.0;
  for (int s : seeds) {
    heap.emplace_back(sign * u[static_cast<std::size_t>(s)](c), s);
    std::push_heap(heap.begin(), heap.end());
  }
  int moved = 0;
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end());
    const auto [key, a] = heap.back();
    heap.pop_back();
    const double ua = u[static_cast<std::size_t>(a)](c);
    if (sign * ua != key) continue;  // a stale entry
    for (int h = first_[static_cast<std::size_t>(a)]; h < first_[static_cast<std::size_t>(a) + 1]; ++h) {
      const Half& half = halves_[static_cast<std::size_t>(h)];
      double& ub = u[static_cast<std::size_t>(half.other)](c);
      // Raise: b may not lag below u_a + lo. Lower: b may not stay above u_a + hi.
      const double bound = ua + (raise ? half.lo[c] : half.hi[c]);
      if (raise ? ub >= bound : ub <= bound) continue;
      if (pinned[static_cast<std::size_t>(half.other)]) {
        ++blocked;
        continue;
      }
      undo_.push_back({half.other, c, ub});
      ub = bound;
      ++moved;
      heap.emplace_back(sign * ub, half.other);
      std::push_heap(heap.begin(), heap.end());
    }
  }
  return moved;
}

ChainMail::MoveReport ChainMail::Move(std::span<const int> drivers, std::span<const Eigen::Vector3d> targets,
                                      std::span<Eigen::Vector3d> u, Drivers mode, std::span<const int> also_pinned) {
  if (drivers.size() != targets.size()) throw std::invalid_argument("ChainMail move: one target per driver");
  if (u.size() != fixed_.size()) throw std::invalid_argument("ChainMail move: one displacement per element");
  Finalise();
  std::vector<std::uint8_t>& pinned = pinned_scratch_;
  for (std::size_t i = 0; i < fixed_.size(); ++i) pinned[i] = fixed_[i];
  if (mode == Drivers::kPinned)
    for (int d : drivers) pinned[static_cast<std::size_t>(d)] = 1;
  for (int p : also_pinned) pinned[static_cast<std::size_t>(p)] = 1;
  MoveReport report;
  undo_.clear();
  std::vector<int> up, down;
  for (int c = 0; c < 3; ++c) {
    up.clear();
    down.clear();
    for (std::size_t i = 0; i < drivers.size(); ++i) {
      double& ud = u[static_cast<std::size_t>(drivers[i])](c);
      if (targets[i](c) > ud) up.push_back(drivers[i]);
      if (targets[i](c) < ud) down.push_back(drivers[i]);
      undo_.push_back({drivers[i], c, ud});
      ud = targets[i](c);
    }
    report.moved += Pass(up, c, true, u, pinned, report.blocked);
    report.moved += Pass(down, c, false, u, pinned, report.blocked);
  }
  if (report.refused()) {  // put everything back, latest first
    for (auto it = undo_.rbegin(); it != undo_.rend(); ++it)
      u[static_cast<std::size_t>(it->element)](it->coordinate) = it->value;
    report.moved = 0;
  }
  return report;
}

double ChainMail::WorstViolation_m(std::span<const Eigen::Vector3d> u) const {
  Finalise();
  double worst = 0.0;
  const auto n = static_cast<int>(fixed_.size());
  for (int a = 0; a < n; ++a)
    for (int h = first_[static_cast<std::size_t>(a)]; h < first_[static_cast<std::size_t>(a) + 1]; ++h) {
      const Half& half = halves_[static_cast<std::size_t>(h)];
      const Eigen::Vector3d d = u[static_cast<std::size_t>(half.other)] - u[static_cast<std::size_t>(a)];
      for (int c = 0; c < 3; ++c) worst = std::max({worst, half.lo[c] - d(c), d(c) - half.hi[c]});
    }
  return worst;
}

std::vector<double> ChainMail::SlackFrom(std::span<const int> from, int c, bool raise) const {
  Finalise();
  std::vector<double> slack(fixed_.size(), INFINITY);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (int f : from) {
    slack[static_cast<std::size_t>(f)] = 0.0;
    queue.emplace(0.0, f);
  }
  while (!queue.empty()) {
    const auto [d, a] = queue.top();
    queue.pop();
    if (d != slack[static_cast<std::size_t>(a)]) continue;
    for (int h = first_[static_cast<std::size_t>(a)]; h < first_[static_cast<std::size_t>(a) + 1]; ++h) {
      const Half& half = halves_[static_cast<std::size_t>(h)];
      const double step = raise ? -double(half.lo[c]) : double(half.hi[c]);
      const double next = d + step;
      if (next < slack[static_cast<std::size_t>(half.other)]) {
        slack[static_cast<std::size_t>(half.other)] = next;
        queue.emplace(next, half.other);
      }
    }
  }
  return slack;
}

}  // namespace vesica::physics
