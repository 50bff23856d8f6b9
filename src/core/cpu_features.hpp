#pragma once
// Run-time choice between the hand-vectorised and the generic form of a kernel (x86-64 with GCC
// or Clang). The vectorised form runs where the CPU has its instruction set and no test switched
// it off; both forms must give the same bits, and the tests run both on the same machine.
#if defined(__x86_64__) && defined(__GNUC__)
#define GF_X86_SIMD 1  // intrinsics of <immintrin.h> and target attributes can be compiled
#endif

namespace gf {

enum class InstructionSet {
  Avx2,
  Avx512fAvx2,  // AVX-512F together with AVX2
  Avx512fVl,    // AVX-512F with the VL extension (AVX-512 operations on 256-bit registers)
};

/// Whether this CPU has the instruction set (asked once per set).
inline bool cpuHas(InstructionSet set) {
#if defined(GF_X86_SIMD)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  static const bool avx512f = __builtin_cpu_supports("avx512f");
  static const bool avx512vl = __builtin_cpu_supports("avx512vl");
  switch (set) {
    case InstructionSet::Avx2: return avx2;
    case InstructionSet::Avx512fAvx2: return avx512f && avx2;
    case InstructionSet::Avx512fVl: return avx512f && avx512vl;
  }
#else
  (void)set;
#endif
  return false;
}

/// A kernel's switch between its vectorised form (needing `set`) and its generic one.
class VectorForm {
 public:
  explicit VectorForm(InstructionSet set) : set_(set) {}
  /// The vectorised form may run: the CPU has the set and no test switched the form off.
  bool enabled() const { return allowed_ && cpuHas(set_); }
  /// Tests: false runs the generic form on a CPU that has the set.
  void allow(bool allowed) { allowed_ = allowed; }

 private:
  InstructionSet set_;
  bool allowed_ = true;
};

}  // namespace gf
