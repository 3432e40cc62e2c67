// A fixed table of named entries (materials, motion models, integrators): the one place their
// names are written. Lookup is by exact name; an unknown name is an InvalidArgument that lists
// the known names in table order, so help texts and errors derived from a table cannot disagree
// with it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "virtual_go/common/formatting.h"
#include "virtual_go/common/validation.h"

namespace virtual_go {

// Entry: any struct with a std::string `name`.
template <class Entry>
class NameTable {
 public:
  // what: the kind of entry for messages ("stone material"); field: InvalidArgument::field().
  NameTable(std::string what, std::string field, std::vector<Entry> entries)
      : what_(std::move(what)), field_(std::move(field)), entries_(std::move(entries)) {}

  // nullptr when there is no entry of that name.
  const Entry* find(const std::string& name) const {
    for (const Entry& e : entries_) {
      if (e.name == name) return &e;
    }
    return nullptr;
  }
  // Throws InvalidArgument "unknown <what> '<name>' (known: a b c)"; a long name is cut.
  const Entry& at(const std::string& name) const {
    if (const Entry* e = find(name)) return *e;
    throw InvalidArgument(field_, "unknown " + what_ + " " + quote_user_text(name) +
                                      " (known: " + join(names(), " ") + ")");
  }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const Entry& e : entries_) out.push_back(e.name);
    return out;
  }
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  std::string what_;
  std::string field_;
  std::vector<Entry> entries_;
};

}  // namespace virtual_go
