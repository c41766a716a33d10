#pragma once
// A scalar function of simulated time, as scenes give loads: constant, linear ramp, or a
// piecewise-linear table (held constant outside its range).
#include <limits>
#include <utility>
#include <vector>

namespace rift {

struct TimeFunction {
  enum class Kind { constant, ramp, table };
  Kind kind = Kind::constant;
  double value = 0.0;       // constant: the value; ramp: value up to start_time
  double start_time = 0.0;  // ramp: when the ramp begins [s]
  double rate = 0.0;        // ramp: d(value)/dt after start_time [unit/s]
  double limit = 0.0;       // ramp: value at which it stops growing (ignored when !has_limit)
  bool has_limit = false;
  std::vector<std::pair<double, double>> points;  // table: (time, value), strictly increasing time

  double operator()(double t) const;
  // Smallest and largest value over all times (a ramp without limit is unbounded on one side).
  double lowest() const;
  double highest() const;
};

inline double TimeFunction::lowest() const {
  switch (kind) {
    case Kind::constant:
      return value;
    case Kind::ramp:
      return rate >= 0 ? value : (has_limit ? limit : -std::numeric_limits<double>::infinity());
    case Kind::table: {
      double v = points.empty() ? 0.0 : points.front().second;
      for (const auto& p : points) v = p.second < v ? p.second : v;
      return v;
    }
  }
  return value;
}

inline double TimeFunction::highest() const {
  switch (kind) {
    case Kind::constant:
      return value;
    case Kind::ramp:
      return rate <= 0 ? value : (has_limit ? limit : std::numeric_limits<double>::infinity());
    case Kind::table: {
      double v = points.empty() ? 0.0 : points.front().second;
      for (const auto& p : points) v = p.second > v ? p.second : v;
      return v;
    }
  }
  return value;
}

inline double TimeFunction::operator()(double t) const {
  switch (kind) {
    case Kind::constant:
      return value;
    case Kind::ramp: {
      double v = t <= start_time ? value : value + rate * (t - start_time);
      if (has_limit && ((rate >= 0 && v > limit) || (rate < 0 && v < limit))) v = limit;
      return v;
    }
    case Kind::table: {
      if (points.empty()) return 0.0;
      if (t <= points.front().first) return points.front().second;
      if (t >= points.back().first) return points.back().second;
      size_t hi = 1;
      while (points[hi].first < t) ++hi;
      const auto& [t0, v0] = points[hi - 1];
      const auto& [t1, v1] = points[hi];
      return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
    }
  }
  return 0.0;
}

}  // namespace rift
