#pragma once
// Everything a program chaining vplkit stages needs.

#include "vplkit/barriers.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/device_info.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/validation.hpp"
