// Aligned blocks for image pixels (image.h, CacheLineAllocator). A large block is aligned to 2 MiB and, on
// Linux, advised MADV_HUGEPAGE: with transparent huge pages in "madvise" mode (Debian's default) the kernel
// then backs it with 2 MiB pages, and reading a 1024 x 512 map or filling a prefix table faults once per
// 2 MiB. The advice is a hint: where it is refused (another kernel, THP "never") the block is the same
// memory with 4 KiB pages.
#include "shadelab/image/image.h"

#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace shadelab {

namespace {

constexpr std::size_t line_alignment = 64;
constexpr std::size_t huge_alignment = std::size_t{2} << 20;

std::align_val_t alignment_of(std::size_t bytes) {
  return std::align_val_t{bytes >= buffer_huge_bytes ? huge_alignment : line_alignment};
}

// A large block is rounded up to whole 2 MiB pages (at most 2 MiB - 4 bytes more: a 512 x 512 face of 3 MiB
// takes 4), so that its tail is a huge page too.
std::size_t block_bytes(std::size_t bytes) {
  return bytes >= buffer_huge_bytes ? (bytes + huge_alignment - 1) / huge_alignment * huge_alignment : bytes;
}

}  // namespace

void* allocate_buffer(std::size_t bytes) {
  if (bytes > (std::size_t{1} << 62)) throw std::bad_alloc();  // so that the rounding up cannot wrap
  const std::size_t block = block_bytes(bytes);
  void* p = ::operator new(block, alignment_of(bytes));
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // The advice only changes how the block's pages are backed; where it is refused nothing else changes.
  if (bytes >= buffer_huge_bytes) (void)::madvise(p, block, MADV_HUGEPAGE);
#endif
  return p;
}

void free_buffer(void* p, std::size_t bytes) noexcept { ::operator delete(p, alignment_of(bytes)); }

}  // namespace shadelab
