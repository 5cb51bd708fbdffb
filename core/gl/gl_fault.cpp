// core/gl/gl_fault.cpp — see gl_fault.h.
#include "core/gl/gl_fault.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdlib>
#include <mutex>
#include <type_traits>
#include <vector>

#include "core/base/errors.h"

namespace sl {
namespace {

// The armed fault is process state beside the current GL context (a render thread meets it,
// a test arms it). `fault` is written only while `armed` is false (injectGlFault), read only
// after `armed` was seen true.
struct ArmedFault {
  std::atomic<bool> armed{false};
  GlFault fault;
  std::atomic<long long> passes{0};  // PassTimers begun since arming (pass#N)
  std::atomic<long long> calls{0};   // GL calls through the fault table since arming (call#N)
  std::atomic<int> fired{0};
  std::once_flag variableRead;
  std::mutex arming;
};
ArmedFault gFault;

// This thread's side: the context table the fault table forwards to, whether the fault table
// was made current, what a fired fault left to do, and the open passes (to name them).
thread_local const GlDispatch* tInner = nullptr;
thread_local bool tInstalled = false;
thread_local bool tErrorPending = false;  // the next glGetError reports GL_INVALID_OPERATION
thread_local bool tMissingNext = false;   // the next GL call finds no entry point
thread_local std::string tNote;
thread_local std::vector<std::string> tOpenPasses;

void armFault(const GlFault& fault) {
  std::lock_guard<std::mutex> lock(gFault.arming);
  gFault.armed.store(false);
  gFault.fault = fault;
  gFault.passes.store(0);
  gFault.calls.store(0);
  tErrorPending = false;
  tMissingNext = false;
  tNote.clear();
  gFault.armed.store(true, std::memory_order_release);
}

void readVariableOnce() {
  std::call_once(gFault.variableRead, [] {
    const char* value = std::getenv(kGlFaultVariable);
    if (value != nullptr && *value != '\0') armFault(parseGlFault(value));
  });
}

// Disarms and returns true for exactly one caller: the fault fires once per arming.
bool fire() {
  bool expected = true;
  if (!gFault.armed.compare_exchange_strong(expected, false)) return false;
  ++gFault.fired;
  tNote = " (injected GL fault " + gFault.fault.spelling +
          (tOpenPasses.empty() ? std::string(", outside any pass)")
                               : ", in pass '" + tOpenPasses.back() + "')");
  return true;
}

// One entry of the fault table: counts the call (call#N), then forwards to this thread's
// context table exactly as core/gl/gl.h's Forward does, absent entries included.
template <class Fn, class Entry>
struct Faulty;
template <class R, class... Args, class Entry>
struct Faulty<R (*)(Args...), Entry> {
  static R call(Args... args) {
    if (tMissingNext) {
      tMissingNext = false;
      gl::throwMissingEntryPoint(Entry::kName);
    }
    if (gFault.armed.load(std::memory_order_acquire) &&
        gFault.fault.trigger == GlFault::Trigger::kCallNumber &&
        ++gFault.calls == gFault.fault.number && fire()) {
      if (gFault.fault.kind == GlFault::Kind::kMissingEntryPoint)
        gl::throwMissingEntryPoint(Entry::kName);
      tErrorPending = true;  // the call is made, and fails (the next glGetError says so)
    }
    auto fn = tInner == nullptr ? nullptr : tInner->*Entry::kMember;
    if (fn == nullptr) gl::throwMissingEntryPoint(Entry::kName);
    if constexpr (std::is_same_v<Entry, gl::entry::GetError>) {
      if (tErrorPending) {
        tErrorPending = false;
        return GL_INVALID_OPERATION;
      }
    }
    return fn(args...);
  }
};

const GlDispatch& faultTable() {
  static const GlDispatch table = [] {
    GlDispatch t;
#define SL_GL(name) t.name = &Faulty<decltype(&::gl##name), gl::entry::name>::call;
#include "core/gl/gl_functions.inc"
#undef SL_GL
    return t;
  }();
  return table;
}

// A pass-table id as the tables spell them: letters, digits, '-' and '_' ("3", "5b", "mesh").
bool isPassId(const std::string& id) {
  return !id.empty() && std::all_of(id.begin(), id.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_';
  });
}

long long positiveCount(const std::string& digits, const std::string& spelling) {
  const bool allDigits = !digits.empty() && digits.size() <= 18 &&
                         digits.find_first_not_of("0123456789") == std::string::npos;
  const long long n = allDigits ? std::stoll(digits) : 0;
  if (n < 1)
    throw InputError(std::string(kGlFaultVariable) + ": the count after '#' must be a whole " +
                     "number from 1, got '" + spelling + "'");
  return n;
}

}  // namespace

GlFault parseGlFault(const std::string& text) {
  const std::string forms =
      " (KIND@TRIGGER: KIND error or missing, TRIGGER pass=ID, "
      "pass#N or call#N)";
  GlFault f;
  f.spelling = text;
  const size_t at = text.find('@');
  if (at == std::string::npos)
    throw InputError(std::string(kGlFaultVariable) + ": no '@' in '" + text + "'" + forms);
  const std::string kind = text.substr(0, at), trigger = text.substr(at + 1);
  if (kind == "error") {
    f.kind = GlFault::Kind::kError;
  } else if (kind == "missing") {
    f.kind = GlFault::Kind::kMissingEntryPoint;
  } else {
    throw InputError(std::string(kGlFaultVariable) + ": unknown fault kind '" + kind + "' in '" +
                     text + "'" + forms);
  }
  if (trigger.rfind("pass=", 0) == 0 && trigger.size() > 5) {
    f.trigger = GlFault::Trigger::kPassId;
    f.passId = trigger.substr(5);
    if (!isPassId(f.passId))
      throw InputError(std::string(kGlFaultVariable) + ": pass= takes a pass id of the " +
                       "technique's pass table (pass=3, pass=5b, pass=mesh), got '" + f.passId +
                       "' in '" + text + "'");
  } else if (trigger.rfind("pass#", 0) == 0) {
    f.trigger = GlFault::Trigger::kPassNumber;
    f.number = positiveCount(trigger.substr(5), text);
  } else if (trigger.rfind("call#", 0) == 0) {
    f.trigger = GlFault::Trigger::kCallNumber;
    f.number = positiveCount(trigger.substr(5), text);
  } else {
    throw InputError(std::string(kGlFaultVariable) + ": unknown trigger '" + trigger + "' in '" +
                     text + "'" + forms);
  }
  return f;
}

void injectGlFault(const GlFault& fault) {
  readVariableOnce();  // the variable, read later, must not replace the test's fault
  armFault(fault);
}

void clearGlFault() {
  readVariableOnce();
  gFault.armed.store(false);
  tErrorPending = false;
  tMissingNext = false;
  tNote.clear();
}

int glFaultsFired() { return gFault.fired.load(); }

bool glFaultArmed() {
  readVariableOnce();
  return gFault.armed.load(std::memory_order_acquire);
}

const GlDispatch* glFaultLayer(const GlDispatch* table) {
  tInstalled = table != nullptr && glFaultArmed();
  tOpenPasses.clear();
  if (!tInstalled) return table;
  tInner = table;
  return &faultTable();
}

std::string armedGlFaultPassId() {
  if (!glFaultArmed() || gFault.fault.trigger != GlFault::Trigger::kPassId) return "";
  return gFault.fault.passId;
}

void glFaultPassBegin(const std::string& id, const std::string& name) {
  if (!tInstalled) return;
  tOpenPasses.push_back(name);
  if (!gFault.armed.load(std::memory_order_acquire)) return;
  const GlFault& f = gFault.fault;
  bool met = false;
  if (f.trigger == GlFault::Trigger::kPassNumber) met = ++gFault.passes == f.number;
  if (f.trigger == GlFault::Trigger::kPassId) met = !id.empty() && id == f.passId;
  if (!met || !fire()) return;
  if (f.kind == GlFault::Kind::kError)
    tErrorPending = true;
  else
    tMissingNext = true;
}

void glFaultPassEnd() {
  if (tInstalled && !tOpenPasses.empty()) tOpenPasses.pop_back();
}

std::string takeGlFaultNote() {
  std::string note;
  note.swap(tNote);
  return note;
}

}  // namespace sl
