#pragma once
// to[k] = from[order[k]]: the gather every move of particles is made of.
#include "core/hd.hpp"
#include "core/types.hpp"

namespace gs {

template <class T>
struct Gather {
  const T* from;
  T* to;
  const Index* order;
  GS_HD void operator()(Index k) const { to[k] = from[order[k]]; }
};

}  // namespace gs
