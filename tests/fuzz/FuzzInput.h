#pragma once
// What every fuzz target shares: the readers under test take file paths, so each input is
// written to a file in one temporary folder of the process (made on first use, removed at exit),
// under the name the reader dispatches on.

#include <cstddef>
#include <cstdint>
#include <string>

namespace weft::fuzz {

// The process's temporary folder (made on first use).
const std::string& processFolder();

// Writes `size` bytes to <process temporary folder>/<name> and returns that path.
std::string writeInput(const std::string& name, const std::uint8_t* data, std::size_t size);

}  // namespace weft::fuzz
