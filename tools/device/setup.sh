# Sourced by the device scripts: the Vulkan loader carried in .gl/ and NVIDIA's driver.
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json

# The binaries a like-for-like call compares, from BINS (default "before irradiant", in .dev/),
# as the array `bins`, and the same in reverse order as `reversed`, for the second round.
compared_binaries() {
    bins=(${BINS:-before irradiant})
    reversed=$(printf '%s\n' "${bins[@]}" | tac)
}
