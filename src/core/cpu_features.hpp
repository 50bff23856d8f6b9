#pragma once
// Run-time choice between the hand-vectorised and the generic form of a kernel (x86-64 with GCC
// or Clang). The vectorised form runs where the CPU has its instruction set and no test switched
// it off; both forms must give the same bits, and the tests run both on the same machine.
#if defined(__x86_64__) && defined(__GNUC__)
#define GF_X86_SIMD 1  // intrinsics of <immintrin.h> and target attributes can be compiled
#include <cpuid.h>
#endif

// GF_VECTOR_CLONES before a function: GCC compiles it also for AVX2 and AVX-512 and picks the form
// at run time by the CPU (the generic x86-64 build otherwise vectorises with SSE2). The build uses
// -ffp-contract=off, so no clone fuses a multiply and an add: the same results on every CPU. Not
// under Clang: Clang (14) cannot clone function templates, so it (and clang-tidy) compiles the
// generic form only.
#if defined(GF_X86_SIMD) && !defined(__clang__) && defined(__linux__) && !defined(__AVX512F__)
#define GF_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define GF_VECTOR_CLONES
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

/// Whether this CPU has PREFETCHW (CPUID 0x80000001 ECX bit 8, "3dnowprefetch" in /proc/cpuinfo:
/// every AMD64 CPU, Intel since Broadwell).
inline bool cpuHasPrefetchW() {
#if defined(GF_X86_SIMD)
  static const bool has = [] {
    unsigned a = 0, b = 0, c = 0, d = 0;
    return __get_cpuid(0x80000001u, &a, &b, &c, &d) != 0 && (c & (1u << 8)) != 0;
  }();
  return has;
#else
  return false;
#endif
}

/// Requests the cache line at p for writing: PREFETCHW, so the line arrives owned and a store to
/// a line that another core holds does not wait for its invalidation. Only where
/// cpuHasPrefetchW() (the caller asks once, outside its loop); GCC emits a plain read prefetch for
/// __builtin_prefetch(p, 1) in the generic x86-64 build (no -mprfchw). Never faults.
inline void prefetchForWrite(const void* p) {
#if defined(GF_X86_SIMD)
  asm volatile("prefetchw %0" ::"m"(*static_cast<const char*>(p)));
#else
  __builtin_prefetch(p, 1);
#endif
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
