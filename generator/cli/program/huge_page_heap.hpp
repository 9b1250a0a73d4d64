#pragma once
// Transparent huge pages for pfgen's heap.
//
// A derivation allocates millions of small objects (GiNaC numbers, polynomial terms): `pfgen
// derive` of the dense cubic n = 20 benchmark model touches about 420 MB of heap, about 100 000
// page faults and as many TLB misses in 4 kB pages. glibc's malloc can ask the kernel for 2 MB
// transparent huge pages instead (its tunable glibc.malloc.hugetlb=1, glibc 2.35 and later), but
// glibc reads tunables only when a process starts. So main() calls this first: with
// PFGEN_HUGE_PAGES=1, and where it can help, pfgen executes itself once more with the tunable
// added to GLIBC_TUNABLES, same arguments, same process id. It is opt-in because it pays on some
// machines and costs on others (the kernel clears each 2 MB page on first touch): the whole
// command at n = 20 took 1.6x less time with it on one machine and 1.3x more on another of the
// same kind. Where it cannot help (not glibc, glibc older than 2.35, the kernel's
// transparent_hugepage setting "never" or already "always", the tunable already set) it does
// nothing; if the execution fails, pfgen continues with the heap as it is. Nothing pfgen computes
// or prints depends on the page size.
namespace pfgen::cli {

void use_huge_page_heap(char** argv);

}  // namespace pfgen::cli
