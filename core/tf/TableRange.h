#pragma once

// Internal to core/tf: the argument checks the table builders share.

namespace lucent::detail {

// Throws std::invalid_argument unless size >= 2 and lo < hi are finite.
void checkTableRange(double lo, double hi, int size);

} // namespace lucent::detail
