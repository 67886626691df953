// The arithmetic a backend runs the kernel in: the CLI's --precision and
// its one list of names (render/cpu takes it in CpuOptions::precision).
#pragma once

#include <string>
#include <vector>

namespace blurcull::frontend {

// The kernel's arithmetic: kernel<double> (the reference) or kernel<float>,
// the arithmetic of the kernel's GLSL and so of the GL backend.
enum class KernelPrecision { float64, float32 };

struct KernelPrecisionInfo {
    KernelPrecision precision;
    const char* name;  // what the command takes and prints
    const char* help;  // one line
};

// Every precision, in the order of the enum: the one list of their names.
const std::vector<KernelPrecisionInfo>& kernel_precisions();

// "double" or "float".
const char* to_string(KernelPrecision precision);

// The names of kernel_precisions(), in order.
std::vector<std::string> kernel_precision_names();

// "double" or "float"; throws std::invalid_argument("kernel precision 'x' is
// not double or float") otherwise.
KernelPrecision parse_kernel_precision(const std::string& name);

}  // namespace blurcull::frontend
