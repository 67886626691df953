#include "render/common/kernel_precision.hpp"

#include <stdexcept>

namespace blurcull::frontend {

const std::vector<KernelPrecisionInfo>& kernel_precisions() {
    static const std::vector<KernelPrecisionInfo> precisions = {
        {KernelPrecision::float64, "double", "kernel<double>, the reference"},
        {KernelPrecision::float32, "float", "kernel<float>, the gl backend's arithmetic"},
    };
    return precisions;
}

const char* to_string(KernelPrecision precision) {
    return kernel_precisions()[static_cast<std::size_t>(precision)].name;
}

std::vector<std::string> kernel_precision_names() {
    std::vector<std::string> names;
    for (const KernelPrecisionInfo& info : kernel_precisions()) names.emplace_back(info.name);
    return names;
}

KernelPrecision parse_kernel_precision(const std::string& name) {
    std::string valid;
    for (const KernelPrecisionInfo& info : kernel_precisions()) {
        if (name == info.name) return info.precision;
        valid += (valid.empty() ? "" : " or ") + std::string(info.name);
    }
    throw std::invalid_argument("kernel precision '" + name + "' is not " + valid);
}

}  // namespace blurcull::frontend
