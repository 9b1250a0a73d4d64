#include "pfgen/model/polynomial_shape.hpp"

#include <algorithm>
#include <map>

namespace pfgen {
namespace {

class ShapeWalk {
 public:
  ShapeWalk(const std::vector<GiNaC::symbol>& variables, std::int64_t cap) : n_(variables.size()), cap_(cap) {
    for (std::size_t k = 0; k < variables.size(); ++k) index_.emplace(variables[k], k);
  }

  // One node's answer: polynomial, whether a variable occurs in it, and its degrees (empty when
  // no variable occurs: all zero).
  struct Node {
    bool polynomial = true;
    bool has_variable = false;
    std::vector<std::int64_t> degrees;
  };

  Node walk(const GiNaC::ex& e) const {
    Node node = walk_node(e);
    // A node with a variable always carries all n degrees (zero in a non-polynomial part).
    if (node.has_variable && node.degrees.empty()) node.degrees.assign(n_, 0);
    return node;
  }

 private:
  Node walk_node(const GiNaC::ex& e) const {
    if (GiNaC::is_exactly_a<GiNaC::symbol>(e)) {
      Node node;
      auto found = index_.find(e);
      if (found != index_.end()) {
        node.has_variable = true;
        node.degrees.assign(n_, 0);
        node.degrees[found->second] = 1;
      }
      return node;
    }
    if (GiNaC::is_exactly_a<GiNaC::add>(e) || GiNaC::is_exactly_a<GiNaC::mul>(e)) {
      // A sum's degree is its terms' largest, a product's its factors' sum (the ops of a product
      // are its factors with their powers, so each power is checked below).
      const bool sum = GiNaC::is_exactly_a<GiNaC::add>(e);
      Node node;
      for (std::size_t k = 0; k < e.nops(); ++k) {
        Node part = walk(e.op(k));
        node.polynomial = node.polynomial && part.polynomial;
        if (!part.has_variable) continue;
        if (!node.has_variable) {
          node = Node{node.polynomial, true, std::move(part.degrees)};
          continue;
        }
        for (std::size_t v = 0; v < n_; ++v)
          node.degrees[v] = sum ? std::max(node.degrees[v], part.degrees[v]) : capped(node.degrees[v] + part.degrees[v]);
      }
      return node;
    }
    if (GiNaC::is_exactly_a<GiNaC::power>(e)) {
      Node base = walk(e.op(0));
      const GiNaC::ex& exponent = e.op(1);
      const bool exponent_has_variable = has_variable(exponent);
      Node node;
      node.has_variable = base.has_variable || exponent_has_variable;
      if (!base.polynomial) {
        node.polynomial = false;
      } else if (base.has_variable) {
        node.polynomial = exponent.info(GiNaC::info_flags::nonnegint);
      } else {
        node.polynomial = !exponent_has_variable;
      }
      if (base.has_variable && node.polynomial) {
        const GiNaC::numeric& k = GiNaC::ex_to<GiNaC::numeric>(exponent);
        const bool huge = k > GiNaC::numeric(cap_);
        node.degrees.assign(n_, 0);
        for (std::size_t v = 0; v < n_; ++v)
          if (base.degrees[v] > 0) node.degrees[v] = huge ? cap_ + 1 : capped(base.degrees[v] * k.to_long());
      }
      return node;
    }
    // Anything else (a number, a constant, a function call): polynomial when no variable is in it.
    Node node;
    node.has_variable = e.nops() > 0 && has_variable(e);
    node.polynomial = !node.has_variable;
    return node;
  }

  bool has_variable(const GiNaC::ex& e) const {
    for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
      if (GiNaC::is_exactly_a<GiNaC::symbol>(*it) && index_.count(*it)) return true;
    return false;
  }
  // Degrees are at most cap + 1 each, so a product of two stays far inside int64.
  std::int64_t capped(std::int64_t degree) const { return std::min(degree, cap_ + 1); }

  std::size_t n_;
  std::int64_t cap_;
  std::map<GiNaC::ex, std::size_t, GiNaC::ex_is_less> index_;
};

}  // namespace

PolynomialShape polynomial_shape(const GiNaC::ex& e, const std::vector<GiNaC::symbol>& variables, std::int64_t cap) {
  ShapeWalk::Node node = ShapeWalk(variables, cap).walk(e);
  PolynomialShape shape;
  shape.polynomial = node.polynomial;
  shape.degrees = node.has_variable ? std::move(node.degrees) : std::vector<std::int64_t>(variables.size(), 0);
  return shape;
}

}  // namespace pfgen
