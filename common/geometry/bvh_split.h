#pragma once

// The pieces of one split of the BVH builder (bvh_build.cpp): a node's boxes,
// the SAH's centroid bins, and the partition that measures both halves while
// it moves the primitives. Each works on four lanes (x, y, z and a free one)
// and rounds exactly as the scalar Bounds3 arithmetic would, so the tree is
// the one the scalar builder made, byte for byte.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "common/geometry/bvh.h"

namespace glint {

// One box as two four-lane vectors (lanes 0-2: x, y, z; lane 3 free), so
// that a union is two vector instructions. The comparisons are glm::min's
// and glm::max's, lane by lane, so the planes come out as Bounds3::expand
// makes them.
struct Box4 {
  Float4 lo;  // trivial, so that arrays of bins cost nothing until used
  Float4 hi;

  static Box4 empty() { return {Float4{} + kInfinity, Float4{} - kInfinity}; }

  void expand(const Box4& b) {
    lo = b.lo < lo ? b.lo : lo;
    hi = hi < b.hi ? b.hi : hi;
  }
  void expand(const Float4& p) { expand(Box4{p, p}); }
  // 0.5 (min + max), as Bounds3::centre; lane 3 is 0, whatever bits it held
  // (arithmetic on an id's bits, a subnormal float, would cost 100 cycles).
  Float4 centre() const {
    constexpr Mask4 kXyz{-1, -1, -1, 0};
    const auto xyz = [](Float4 v) { return reinterpret_cast<Float4>(reinterpret_cast<Mask4>(v) & kXyz); };
    return 0.5f * (xyz(lo) + xyz(hi));
  }
  Bounds3 bounds() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
  float surfaceArea() const { return bounds().surfaceArea(); }
};

// What the builder sees of a primitive, 32 bytes: its box, its id in the
// bits of lo's free lane 3 (which no union of boxes reads back), and in hi's
// lane 3 whether it is tested alone (1: a sphere) or may join a block (0: a
// triangle). A union keeps the larger hi, so a node's box says whether any
// of its primitives is tested alone (NodeBox::blocksOnly).
struct BuildPrimitive {
  Box4 box;

  BuildPrimitive(const Bounds3& b, std::uint32_t id, bool alone)
      : box{{b.min.x, b.min.y, b.min.z, bitsToFloat(id)}, {b.max.x, b.max.y, b.max.z, alone ? 1.0f : 0.0f}} {}
  std::uint32_t id() const { return floatToBits(box.lo[3]); }
};

constexpr int kMaxBins = 64;  // the most SAH bins per axis BvhSettings::sahBins may ask for

// A node's box and the box of its primitives' centroids.
struct NodeBox {
  Box4 bounds = Box4::empty();
  Box4 centroids = Box4::empty();

  [[gnu::always_inline]] void add(const BuildPrimitive& p) {
    bounds.expand(p.box);
    centroids.expand(p.box.centre());
  }
  // Whether every primitive may join a block (none is tested alone).
  bool blocksOnly() const { return bounds.hi[3] <= 0.0f; }
  static NodeBox of(std::span<const BuildPrimitive> prims) {
    NodeBox box;
    for (const BuildPrimitive& p : prims) box.add(p);
    return box;
  }
};

// A split of a node's primitives, already partitioned: the second half
// starts at mid (0: no split, a leaf), and the halves' boxes.
struct Cut {
  std::size_t mid = 0;
  std::array<NodeBox, 2> sides;

  static Cut at(std::span<const BuildPrimitive> prims, std::size_t mid) {
    if (mid == 0 || mid >= prims.size()) return {mid, {}};
    return {mid, {NodeBox::of(prims.first(mid)), NodeBox::of(prims.subspan(mid))}};
  }
};

// Where centroids fall among the SAH bins of a node, on all three axes at
// once (lane 3 unused). An axis whose centroids all lie in one plane is not
// usable: nothing can be split along it. A centroid's bin is
// (c - lo) * (bins / extent): the quotient once per node and a product per
// primitive, where bins * ((c - lo) / extent) divided per primitive, a
// measurable share of the build (the two may differ by one bin within an
// ulp of a plane).
struct BinGrid {
  int bins;
  Float4 lo;
  Float4 scale;  // bins / extent per axis
  std::array<bool, 3> usable;

  BinGrid(const Box4& centroids, int binCount) : bins(binCount) {
    Float4 extent;
    for (int a = 0; a < 3; ++a) {
      const float e = centroids.hi[a] - centroids.lo[a];
      usable[static_cast<std::size_t>(a)] = e > 0.0f;
      lo[a] = centroids.lo[a];
      extent[a] = e > 0.0f ? e : 1.0f;  // unusable axes: no 0 / 0
    }
    lo[3] = 0.0f;
    extent[3] = 1.0f;
    scale = static_cast<float>(bins) / extent;
  }
  // Per axis: (c - lo) * scale, truncated and clamped to a bin.
  Int4 binOf(const BuildPrimitive& p) const {
    const Float4 t = (p.box.centre() - lo) * scale;
    Int4 i = __builtin_convertvector(t, Int4);
    i = i < 0 ? 0 : i;
    return i > bins - 1 ? bins - 1 : i;
  }
};

// Per axis and bin: how many centroids fell in it and the box of their
// primitives. A bin's box means something only where its count is not 0 (the
// first primitive sets it), so emptying the bins is zeroing the counts.
struct SahBins {
  std::array<std::array<Box4, kMaxBins>, 3> bounds;
  std::array<std::array<int, kMaxBins>, 3> counts;

  // Empties the first `bins` bins of each axis (all a node uses).
  void reset(int bins) {
    for (int a = 0; a < 3; ++a) std::fill_n(counts[a].begin(), bins, 0);
  }

  void add(const BuildPrimitive& p, Int4 bin) {
    for (int a = 0; a < 3; ++a) {
      Box4& box = bounds[a][bin[a]];
      if (counts[a][bin[a]]++ == 0) {
        box = p.box;  // what the empty box's union with it gives, bit for bit
      } else {
        box.expand(p.box);
      }
    }
  }
  // Bins prims a run at a time: the run's bins first, then the updates.
  // Updating each bin as soon as it was computed took about three times as
  // long (docs/performance.md): most likely, an update's load
  // ran before the previous update's store knew its address, was guessed not
  // to alias it, and was thrown away and redone where it did (neighbouring
  // primitives share bins). With the bins in memory, every address is known
  // early. Runs of 8 to 256 measured: 16 to 64 alike in the whole build.
  void add(std::span<const BuildPrimitive> prims, const BinGrid& grid) {
    constexpr std::size_t kRun = 32;
    std::array<Int4, kRun> run;
    for (std::size_t first = 0; first < prims.size(); first += kRun) {
      const std::span<const BuildPrimitive> part = prims.subspan(first, std::min(kRun, prims.size() - first));
      for (std::size_t i = 0; i < part.size(); ++i) run[i] = grid.binOf(part[i]);
      for (std::size_t i = 0; i < part.size(); ++i) add(part[i], run[i]);
    }
  }
};

// Moves the primitives isLeft accepts to the front, in Hoare's scheme (the
// order libstdc++'s std::partition gives), and measures both sides' boxes on
// the way: each primitive is tested and measured once. Returns the first of
// the second side.
template <typename IsLeft>
std::size_t partitionMeasured(std::span<BuildPrimitive> prims, IsLeft isLeft, std::array<NodeBox, 2>& sides) {
  auto first = prims.begin();
  auto last = prims.end();
  const auto at = [&] { return static_cast<std::size_t>(first - prims.begin()); };
  while (true) {
    for (;; ++first) {
      if (first == last) return at();
      if (!isLeft(*first)) break;
      sides[0].add(*first);
    }
    sides[1].add(*first);  // it ends on the right, here or swapped to last
    for (--last;; --last) {
      if (first == last) return at();
      if (isLeft(*last)) break;
      sides[1].add(*last);
    }
    sides[0].add(*last);
    std::iter_swap(first, last);
    ++first;
  }
}

}  // namespace glint
