// The parameter tables as documentation (`superdex params`, docs/parameters.md).
#pragma once

#include <ostream>

namespace superdex {

/// Every parameter table (optim/field_table.h) as markdown: per struct where it is set (scene
/// file, Python), then its fields; then the names of the enums the fields take.
void PrintParameterMarkdown(std::ostream& out);

}  // namespace superdex
