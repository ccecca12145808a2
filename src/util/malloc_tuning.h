// Keep freed heap memory in the process instead of handing it back to the kernel.
//
// glibc serves blocks above 32 MiB with mmap and unmaps them on free, so every large
// activation (the state decoder's are 30-60 MiB for 32 x 400 steps) is page-faulted in anew
// on each use. On this project's VMs a fault costs ~10 us, i.e. ~160 ms per 59 MB tensor:
// a plain torch::mm producing such a tensor ran at 10 GFLOP/s instead of 72, and the whole
// VAE step was ~2x slower. Calling this once per process (training CLIs, benchmarks, tests)
// makes freed blocks reusable; the price is that RSS stays at its peak.
#pragma once

namespace vaegail {

// Idempotent and thread-safe; returns false if glibc refused a setting (other libcs: no-op).
bool retain_freed_memory();

}  // namespace vaegail
