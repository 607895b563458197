// One exception type for every user-facing failure: the message is a single
// line that already names the file and the JSON path or byte offset, so the
// CLI prints it as is.
#pragma once

#include <stdexcept>
#include <string>

namespace rt {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rt
