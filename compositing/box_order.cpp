#include "compositing/box_order.h"

#include <queue>
#include <stdexcept>
#include <string>

namespace sortlast {

namespace {

bool overlapsOn(const Box3& a, const Box3& b, int axis) {
  return std::min(a.hi[axis], b.hi[axis]) > std::max(a.lo[axis], b.lo[axis]);
}

}  // namespace

std::vector<int> backToFrontBoxes(const std::vector<Box3>& boxes, const glm::dvec3& eye) {
  const int n = int(boxes.size());
  std::vector<std::vector<int>> after(static_cast<size_t>(n));  // after[a]: boxes drawn after a
  std::vector<int> before_count(size_t(n), 0);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const Box3 &a = boxes[size_t(i)], &b = boxes[size_t(j)];
      if (isEmpty(a) || isEmpty(b)) continue;
      for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        if (!overlapsOn(a, b, u) || !overlapsOn(a, b, v)) continue;
        int lower = -1, upper = -1;  // separated along `axis`: lower below upper
        if (a.hi[axis] <= b.lo[axis]) lower = i, upper = j;
        else if (b.hi[axis] <= a.lo[axis]) lower = j, upper = i;
        else continue;  // overlapping on all three axes cannot happen for a tiling; leave it
        int first = -1, second = -1;  // first is drawn first (farther)
        if (eye[axis] >= boxes[size_t(upper)].lo[axis]) first = lower, second = upper;
        else if (eye[axis] <= boxes[size_t(lower)].hi[axis]) first = upper, second = lower;
        else break;  // the eye is between the slabs: neither hides the other
        after[size_t(first)].push_back(second);
        ++before_count[size_t(second)];
        break;
      }
    }
  std::vector<int> order;
  for (int i = 0; i < n; ++i)
    if (isEmpty(boxes[size_t(i)])) order.push_back(i);
  std::priority_queue<int, std::vector<int>, std::greater<int>> ready;
  for (int i = 0; i < n; ++i)
    if (!isEmpty(boxes[size_t(i)]) && before_count[size_t(i)] == 0) ready.push(i);
  while (!ready.empty()) {
    int i = ready.top();
    ready.pop();
    order.push_back(i);
    for (int j : after[size_t(i)])
      if (--before_count[size_t(j)] == 0) ready.push(j);
  }
  if (int(order.size()) != n)
    throw std::runtime_error("the ranks' blocks have no back-to-front order from this eye (" +
                             std::to_string(n - int(order.size())) +
                             " blocks in a cycle): use a decomposition whose blocks form a grid");
  return order;
}

}  // namespace sortlast
