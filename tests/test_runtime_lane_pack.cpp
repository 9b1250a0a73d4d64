// The lane-pack tests that run after every step of W runs side by side (FilterStepper::keeps_packs,
// DivergenceGuard::passes_packs, CovarianceGuard::passes_packs_1) decide which lanes go on without
// their one-lane checks. Each is compared here, lane by lane, with the one-lane test it stands for,
// on values chosen to sit on every edge: NaN, infinities, signed zeros, the bound and the
// tolerances themselves, and random states around them. A pack that passed a lane its one-lane
// test fails would let a run go on that should stop; one that failed a passing lane would only
// cost time, and is caught here too.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "pfgen_runtime/filter_stepping.hpp"
#include "pfgen_runtime/guards.hpp"
#include "pfgen_runtime/lane_pack.hpp"

using namespace pfgen_runtime;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The lanes a pass over W lanes keeps: test(packs) ands its verdicts into W / 2 packs of ones.
template <std::size_t W, class Test>
std::vector<bool> lanes_of(Test test) {
  constexpr std::size_t width = lane_pack::kLanes, packs = W / width;
  lane_pack::Pack kept[packs];
  for (lane_pack::Pack& pack : kept) pack = lane_pack::all_set();
  test(kept);
  std::vector<bool> set(W);
  for (std::size_t c = 0; c < packs; ++c) {
    double flags[width];
    lane_pack::store(flags, lane_pack::keep_where(kept[c], lane_pack::splat(1.0)));
    for (std::size_t k = 0; k < width; ++k) set[c * width + k] = flags[k] == 1.0;
  }
  return set;
}

// A value from a pool of edge cases and random magnitudes (either sign).
double edgy(std::mt19937_64& random, double scale) {
  static const double edges[] = {0.0, -0.0, kNaN, kInf, -kInf, 1e-300, -1e-300, 1e8, -1e8, 1e308, -1e308};
  std::uniform_int_distribution<int> pick(0, 3);
  if (pick(random) == 0) return edges[std::uniform_int_distribution<std::size_t>(0, std::size(edges) - 1)(random)];
  std::normal_distribution<double> normal(0.0, scale);
  return normal(random);
}

template <std::size_t W>
void check_keeps(std::size_t n, std::mt19937_64& random) {
  const std::size_t size = filter_state_size(n);
  FilterStepControl control;
  FilterStepper stepper(n, 1, control);
  std::vector<double> before(size * W), after(size * W), one_before(size), one_after(size);
  for (int trial = 0; trial < 300; ++trial) {
    for (std::size_t e = 0; e < size * W; ++e) {
      before[e] = edgy(random, 1.0);
      // Mostly a small change of the entry before, sometimes across the tolerance.
      const double change = std::uniform_int_distribution<int>(0, 1)(random) == 0 ? 0.01 : 0.03;
      after[e] = std::uniform_int_distribution<int>(0, 4)(random) == 0 ? edgy(random, 1.0)
                                                                        : before[e] * (1 + change) + 1e-10;
    }
    const std::vector<bool> packed =
        lanes_of<W>([&](lane_pack::Pack* packs) { stepper.keeps_packs<W>(before.data(), after.data(), packs); });
    for (std::size_t k = 0; k < W; ++k) {
      for (std::size_t e = 0; e < size; ++e) {
        one_before[e] = before[e * W + k];
        one_after[e] = after[e * W + k];
      }
      INFO("n = " << n << ", W = " << W << ", trial " << trial << ", lane " << k);
      CHECK(packed[k] == stepper.keeps(one_before.data(), one_after.data()));
    }
  }
}

template <std::size_t W>
void check_guards(std::mt19937_64& random) {
  const DivergenceGuard bounded(1e8), finite_only(kInf);
  const CovarianceGuard psd;
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t count = std::uniform_int_distribution<std::size_t>(1, 4)(random);
    std::vector<double> values(count * W);
    for (double& value : values) value = edgy(random, 1e8);
    for (const DivergenceGuard* guard : {&bounded, &finite_only}) {
      const std::vector<bool> packed =
          lanes_of<W>([&](lane_pack::Pack* packs) { guard->passes_packs<W>(values.data(), count, packs); });
      std::vector<LaneFlag> flags(W, 1.0);
      guard->pass_lanes(values.data(), count, W, flags.data());
      for (std::size_t k = 0; k < W; ++k) {
        std::vector<double> one(count);
        for (std::size_t i = 0; i < count; ++i) one[i] = values[i * W + k];
        INFO("W = " << W << ", trial " << trial << ", lane " << k << ", bound " << guard->bound());
        CHECK(packed[k] == !guard->check(0.0, one.data(), count).has_value());
        CHECK(packed[k] == (flags[k] != 0));
      }
    }
    // P = [p] for n = 1, on and around the PSD threshold: p >= -(1e-12 + 1e-4 |p|), whose edge is
    // p = -1e-12 / (1 - 1e-4), and random p near it, of either scale.
    const double edge = -1e-12 / (1 - 1e-4);
    std::vector<double> P(W);
    for (std::size_t k = 0; k < W; ++k) {
      switch (std::uniform_int_distribution<int>(0, 3)(random)) {
        case 0: P[k] = std::nextafter(edge, std::uniform_int_distribution<int>(0, 1)(random) ? 0.0 : -1.0); break;
        case 1: P[k] = -std::uniform_real_distribution<double>(0.0, 3e-12)(random); break;
        case 2: P[k] = -1e-4 * std::uniform_real_distribution<double>(0.9, 1.1)(random) * edgy(random, 1.0); break;
        default: P[k] = edgy(random, 1.0);
      }
    }
    const std::vector<bool> packed =
        lanes_of<W>([&](lane_pack::Pack* packs) { psd.passes_packs_1<W>(P.data(), packs); });
    for (std::size_t k = 0; k < W; ++k) {
      const double one[2] = {0.0, P[k]};
      INFO("W = " << W << ", trial " << trial << ", lane " << k << ", P = " << P[k]);
      CHECK(packed[k] == psd.passes_filter_state(one, 1));
    }
  }
}

}  // namespace

TEST_CASE("lane packs: the stepper's packed test keeps exactly the lanes keeps() keeps", "[batch][runtime][unit]") {
  std::mt19937_64 random(7);
  for (std::size_t n : {1, 2, 3}) {
    check_keeps<2>(n, random);
    check_keeps<4>(n, random);
    check_keeps<8>(n, random);
    check_keeps<16>(n, random);
  }
}

TEST_CASE("lane packs: the guards' packed tests pass exactly the lanes their one-lane tests pass",
          "[batch][runtime][unit]") {
  std::mt19937_64 random(11);
  check_guards<2>(random);
  check_guards<4>(random);
  check_guards<8>(random);
  check_guards<16>(random);
}

TEST_CASE("lane packs: the operations act lane by lane, as on doubles", "[batch][runtime][unit]") {
  namespace lp = lane_pack;
  constexpr std::size_t W = 10, width = lp::kLanes;
  const double a[W] = {1.0, -2.0, -0.0, kNaN, -kInf, 3.5, -1e-300, 0.0, 2.0, kInf};
  const double b[W] = {9.0, 8.0, 0.0, 6.0, 5.0, kNaN, 3.0, 2.0, 2.0, kInf};
  auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  for (std::size_t c = 0; c < W; c += width) {
    const lp::Pack x = lp::load(a + c), y = lp::load(b + c);
    double out[width];
    auto lanes = [&](lp::Pack v) {
      lp::store(out, v);
      return out;
    };
    auto flags = [&](lp::Pack mask) { return lanes(lp::keep_where(mask, lp::splat(1.0))); };
    for (std::size_t k = 0; k < width; ++k) {
      const double u = a[c + k], v = b[c + k];
      INFO("lanes " << u << ", " << v);
      CHECK(same(lanes(lp::abs(x))[k], std::abs(u)));
      CHECK(same(lanes(lp::negate(x))[k], -u));
      CHECK(same(lanes(lp::add(x, y))[k], u + v));
      CHECK(same(lanes(lp::subtract(x, y))[k], u - v));
      CHECK(same(lanes(lp::multiply(x, y))[k], u * v));
      CHECK(same(lanes(lp::divide(x, y))[k], u / v));
      CHECK(flags(lp::less(x, y))[k] == (u < v ? 1.0 : 0.0));
      CHECK(flags(lp::less_equal(x, y))[k] == (u <= v ? 1.0 : 0.0));
      CHECK(flags(lp::greater(x, y))[k] == (u > v ? 1.0 : 0.0));
      CHECK(flags(lp::greater_equal(x, y))[k] == (u >= v ? 1.0 : 0.0));
      CHECK(flags(lp::equal(x, y))[k] == (u == v ? 1.0 : 0.0));
      CHECK(flags(lp::not_equal(x, y))[k] == (u != v ? 1.0 : 0.0));
      CHECK(flags(lp::finite(x))[k] == (std::isfinite(u) ? 1.0 : 0.0));
      CHECK(same(lanes(lp::select(lp::less(x, y), x, y))[k], u < v ? u : v));
      CHECK(same(lanes(lp::keep_where(lp::greater(x, y), x))[k], u > v ? u : 0.0));
      CHECK(flags(lp::both(lp::less(x, y), lp::finite(y)))[k] == (u < v && std::isfinite(v) ? 1.0 : 0.0));
      CHECK(flags(lp::either(lp::less(x, y), lp::finite(y)))[k] == (u < v || std::isfinite(v) ? 1.0 : 0.0));
      CHECK(flags(lp::except(lp::finite(x), lp::less(x, y)))[k] == (std::isfinite(u) && !(u < v) ? 1.0 : 0.0));
    }
    CHECK(lp::none(lp::less(x, y)) == !(a[c] < b[c] || a[c + 1] < b[c + 1]));
    CHECK(!lp::none(lp::all_set()));
  }
}
