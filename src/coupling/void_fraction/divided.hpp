#pragma once
// The divided scheme's block path has an AVX-512 form, used where the CPU has it (the same
// stencils bit for bit; divided.cpp). Tests switch it off to check the generic form too.
namespace gf::coupling {

/// Whether the divided scheme may use its AVX-512 block path (default true; a no-op on CPUs
/// without AVX-512). Not thread-safe: set it between coupling steps.
void allowDividedAvx512(bool allowed);

}  // namespace gf::coupling
