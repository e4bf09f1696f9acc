// Memory estimates checked before the large allocations (issue 15, item 3): an atlas, a voxel grid or an
// item buffer the machine cannot hold is refused up front with one line, instead of ending in
// std::bad_alloc, GL_OUT_OF_MEMORY or the kernel's OOM killer hours into a run.
#pragma once

#include <cstdint>
#include <string>

namespace cpgi {

/// The machine's memory (MemTotal of /proc/meminfo) in bytes, or 0 when it cannot be read.
uint64_t physicalMemory();

/// The default limit (the CLI's --max-memory): 75 % of physicalMemory(), leaving the rest to the system
/// and the GL driver; 8 GiB when the machine does not say.
uint64_t defaultMemoryLimit();

/// "1.5 GiB", "300 MiB": bytes for a message.
std::string formatBytes(double bytes);

/// Bytes from "8G", "512M", "1.5GiB", "100000" (plain bytes); 0 when `text` is not such a size.
uint64_t parseByteSize(const std::string& text);

/// Throws InputError(where, "<what> needs about X, more than `maximum memory` Y; <remedy>") when `bytes`
/// passes `limit` (0: no limit).
void requireMemory(double bytes, uint64_t limit, const std::string& where, const std::string& what,
                   const std::string& remedy);

}  // namespace cpgi
