// The tests of curved cells: one call per second-order type.
#pragma once

#include <gtest/gtest.h>

#include <utility>

#include "mesh/curved_type.hpp"

namespace neomesh::testing {

// Calls f.template operator()<Type>() for every second-order type, with the type in the trace.
template <typename F>
void for_each_curved_type(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (([&] {
       SCOPED_TRACE(name(kCurvedTypes[I]));
       f.template operator()<kCurvedTypes[I]>();
     }()),
     ...);
  }
  (std::make_index_sequence<kCurvedTypes.size()>{});
}

}  // namespace neomesh::testing
