#pragma once
// Chemical element symbols, for trajectory formats whose readers expect elements (extended XYZ in
// ASE): a coarse-grained type name is no element.
#include <string>

namespace structmd {

// The atomic number of an element symbol written as in the periodic table ("C", "Na"), else 0.
int atomic_number(const std::string& symbol);

}  // namespace structmd
