#pragma once
// What the public API's handles hold (pfgen/pfgen.hpp), and the guard every call runs under.
// Private to the API's sources: not installed.
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model.hpp"
#include "pfgen/pfgen.hpp"

namespace pfgen::api {

struct Model::Impl {
  pfgen::Model model;
  // The model file when it was read from one (no output may replace it), else empty: the path as
  // given, which messages name as the command names it, and the directory it was relative to.
  std::string file;
  std::string directory;
};

struct Filter::Impl {
  std::shared_ptr<const Model::Impl> model;
  FilterEquations equations;
};

// GiNaC counts the references of its expressions without atomics, and shares numbers and
// symbols between all of them: two threads in GiNaC at once corrupt the counts. Every API call,
// and every destruction of what an API handle holds, runs under this one lock (recursive: a call
// may destroy a handle, or make one, while it holds it).
std::recursive_mutex& api_mutex();

// A handle's contents whose last owner let go while another thread held the lock: destroyed by
// the next call that takes it, so that letting go never waits (a Python thread would wait holding
// the GIL, and every other Python thread with it, for as long as a simulation runs).
void destroy_later(std::function<void()> destroy);
void destroy_pending();

// Runs `work` under the API's lock; an exception that is not pfgen's Error (a library's
// std::invalid_argument or std::runtime_error) becomes one with the same message, so a caller
// catches one type, and its report() is the line the command prints. std::bad_alloc passes.
template <typename Work>
auto guarded(Work&& work) -> decltype(work()) {
  const std::lock_guard<std::recursive_mutex> lock(api_mutex());
  destroy_pending();
  try {
    return work();
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(e.what());
  }
}

// Destroys `p` under the API's lock if it is free, else leaves it to destroy_later.
template <typename T>
void destroy_locked(const T* p) {
  if (api_mutex().try_lock()) {
    delete p;
    api_mutex().unlock();
  } else {
    destroy_later([p] { delete p; });
  }
}

// A shared handle to `value` whose destruction takes the API's lock (destroy_locked).
template <typename T>
std::shared_ptr<const T> locked_shared(T&& value) {
  return std::shared_ptr<const T>(new T(std::forward<T>(value)), [](const T* p) { destroy_locked(p); });
}

// Named values as the command's texts of `option`, "name=value" (names checked by check_no_nul, and
// refused if they hold '='):
// parameters' for --set, a moment filter's moments for --moment.
std::vector<std::string> assignment_texts(const std::map<std::string, double>& values,
                                          const std::string& option = "--set");

// Refuses a string that holds a NUL character: no file name or option of the command can, and
// the C library would read it only up to the NUL (a path "m.yaml\0x" would load m.yaml).
void check_no_nul(const std::string& what, const std::string& text);

// A number option as the command line checks its text: finite, and not below the smallest normal
// magnitude (strtod's range error), in the command's words.
void check_number_option(const std::string& option, double value);

// A number as the text the command line reads back as that decimal (0.1 -> "0.1", exactly 1/10).
std::string number_text(double value);

// A CSV's data rows read back, per column (`columns` of them) its values down the rows: the
// commands write numbers in shortest round-trip form, so strtod gives the very doubles; an empty
// cell (a stopped run, a missing observation) is NaN.
std::vector<Vector> csv_series(const std::string& csv, std::size_t columns);

}  // namespace pfgen::api
