# Sourced by the device scripts: the Vulkan loader carried in .gl/ and NVIDIA's driver.
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
