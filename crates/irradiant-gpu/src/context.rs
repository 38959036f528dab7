//! Adapter choice and device creation, with errors that say how to get a working adapter.

use std::sync::{Arc, Mutex};

use wgpu::{Adapter, Backends, Device, Features, Limits, Queue};

/// What can go wrong with the adapter, the device or the work on it. The messages say what
/// to change wherever the user can act.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// wgpu sees no adapter at all.
    #[error(
        "no GPU adapter found ({tried}). Install a Vulkan driver; with no GPU, Mesa's software driver works: `sudo apt-get install mesa-vulkan-drivers` (Debian/Ubuntu)."
    )]
    NoAdapter {
        /// What was searched (`Vulkan`).
        tried: String,
    },
    /// The [`AdapterChoice`] names an index or a name that no adapter present matches.
    #[error(
        "no adapter matches '{wanted}'. Adapters present: {present}. Pass an index or a part of a name from this list (--adapter or IRRADIANT_ADAPTER)."
    )]
    NoMatchingAdapter {
        /// The index or the part of a name asked for.
        wanted: String,
        /// The adapters present, as `index: name`, comma-separated.
        present: String,
    },
    /// The chosen adapter lacks a limit, feature or texture format Irradiant needs, or
    /// refused to create the device.
    #[error(
        "the adapter '{adapter}' cannot run Irradiant: {reason}. Pick another adapter with --adapter (see `irradiant info`)."
    )]
    Unsuitable {
        /// The adapter's name.
        adapter: String,
        /// What it lacks, or why it refused the device.
        reason: String,
    },
    /// The device reported a validation error (in [`GpuContext::scoped`], or uncaptured
    /// and found by [`GpuContext::check`]).
    #[error("GPU error in {what}: {message}")]
    Validation {
        /// What was being done, as the caller names it (a pass's label).
        what: String,
        /// wgpu's message.
        message: String,
    },
    /// The device was lost: the driver reset it or ran out of memory. Holds wgpu's reason
    /// and message.
    #[error(
        "the GPU device was lost ({0}). The driver reset it or ran out of memory; try a smaller size or fewer samples per frame."
    )]
    DeviceLost(String),
    /// The device refused an allocation for lack of memory. Reported before any other
    /// error, since what fails after it is its consequence.
    #[error(
        "the GPU ran out of memory (noticed in {what}: {message}). Close other programs that use the GPU, or lower the image size, probe counts or bake resolution."
    )]
    OutOfMemory {
        /// What was being done when it was noticed (not necessarily what failed).
        what: String,
        /// wgpu's error with its sources, which say what was being made.
        message: String,
    },
    /// Waiting for the GPU or mapping a readback buffer failed, or a readback asked for a
    /// mip level the texture lacks. Holds the message.
    #[error("waiting for the GPU failed: {0}")]
    Poll(String),
    /// An allocation, or all of a run's together, would pass the adapter's limits or memory
    /// (see [`Budget::check`](crate::Budget::check)); found before anything is allocated.
    #[error(
        "{what} would need {needs}, more than this adapter allows ({allows}): lower {setting}, or pick a larger adapter with --adapter"
    )]
    TooLarge {
        /// The allocation's label (`owner/name`), or "this run" for their sum.
        what: String,
        /// What it would need, for people ("3.0 GiB", "a 20000×10 texture").
        needs: String,
        /// What the adapter allows, for people.
        allows: String,
        /// The setting that sizes it, which the user can lower (`--size`).
        setting: String,
    },
}

/// Which adapter to use: the first usable one, one by index in `irradiant info`'s list, or the
/// first whose name contains a string (case-insensitive).
#[derive(Clone, Debug, Default)]
pub enum AdapterChoice {
    /// The best-ranked adapter: discrete GPUs first, then integrated, virtual, other
    /// and software (CPU) ones.
    #[default]
    Auto,
    /// The adapter at this index of `irradiant info`'s list, from 0.
    Index(usize),
    /// The first adapter whose name contains this, case-insensitive.
    Name(String),
}

impl AdapterChoice {
    /// `IRRADIANT_ADAPTER`, if set, else [`AdapterChoice::Auto`].
    pub fn from_env() -> Self {
        std::env::var("IRRADIANT_ADAPTER")
            .map(|s| Self::parse(&s))
            .unwrap_or_default()
    }

    /// Reads a choice as given on the command line: empty or `auto`, an index, else
    /// a part of an adapter's name.
    pub fn parse(text: &str) -> Self {
        match text.trim() {
            "" | "auto" => Self::Auto,
            t => t
                .parse()
                .map(Self::Index)
                .unwrap_or_else(|_| Self::Name(t.to_owned())),
        }
    }
}

/// What `irradiant info` prints and benchmark records carry.
#[derive(Clone, Debug)]
pub struct GpuInfo {
    /// The adapter's name, as the driver reports it.
    pub name: String,
    /// The backend, as wgpu's `Debug` writes it (`Vulkan`).
    pub backend: String,
    /// The device type, as wgpu's `Debug` writes it (`DiscreteGpu`, `Cpu`).
    pub device_type: String,
    /// The driver's name.
    pub driver: String,
    /// The driver's version and details, as it reports them.
    pub driver_info: String,
    /// Whether the device has timestamp queries, so that passes can be timed.
    pub timestamps: bool,
    /// Largest storage-buffer binding of the device, in bytes.
    pub max_storage_buffer_binding_size: u64,
    /// Largest buffer of the device, in bytes.
    pub max_buffer_size: u64,
    /// Most invocations in x of a compute workgroup on the device.
    pub max_compute_workgroup_size_x: u32,
    /// Storage buffers one shader stage of the device may bind.
    pub max_storage_buffers_per_shader_stage: u32,
    /// Workgroups the device allows in each dimension of a
    /// dispatch.
    pub max_compute_workgroups_per_dimension: u32,
    /// The largest device-local memory heap in bytes, where the driver reports it (Vulkan).
    pub memory: Option<u64>,
    /// Loop iterations one shader invocation may run in all, where the driver ends every loop
    /// past a limit: llvmpipe (lavapipe) shares one counter of 65 535 among all the loops of an
    /// invocation, and past it each loop exits at once, silently (Mesa's
    /// `LP_MAX_TGSI_LOOP_ITERATIONS`). Passes that loop long in one invocation (the path
    /// tracer's samples) split their work to stay under it.
    pub loop_iteration_limit: Option<u32>,
}

/// The adapter and device Irradiant runs on. Device errors are collected rather
/// than left to wgpu's panicking default, and [`check`](Self::check) and
/// [`scoped`](Self::scoped) return them as [`GpuError`] values.
pub struct GpuContext {
    /// The wgpu instance the adapter was found through.
    pub instance: wgpu::Instance,
    /// The chosen adapter.
    pub adapter: Adapter,
    /// The device, with the features and limits Irradiant requests.
    pub device: Device,
    /// The device's queue, which all work is submitted to.
    pub queue: Queue,
    /// Description and limits of the adapter and the device.
    pub info: GpuInfo,
    /// Errors the device reported outside an error scope; taken by [`GpuContext::check`].
    errors: Arc<Mutex<Vec<String>>>,
    /// An allocation the device refused for lack of memory. Reported before any other error:
    /// what fails after it (views and bind groups of the missing resource) is its consequence.
    out_of_memory: Arc<Mutex<Option<String>>>,
    lost: Arc<Mutex<Option<String>>>,
    /// The passes made on this device, by what made them: a technique made again (a preset
    /// changed, a bench's `--vary`, a comparison's second spec) takes its pipelines from here
    /// instead of compiling them again, which on a CPU adapter takes seconds a technique.
    pub(crate) passes:
        Mutex<std::collections::HashMap<crate::pass::PassKey, Arc<crate::ComputePass>>>,
}

/// llvmpipe's limit on the loop iterations of one shader invocation (GpuInfo::loop_iteration_limit).
const LLVMPIPE_LOOP_ITERATIONS: u32 = 65_535;

/// Storage buffers one shader stage may bind: the scene takes 8, a DDGI pass up to 8 more.
const STORAGE_BUFFERS_NEEDED: u32 = 16;

/// Storage textures one shader stage may bind: frame/gbuffer writes its five channels.
const STORAGE_TEXTURES_NEEDED: u32 = 8;

impl GpuContext {
    /// Every adapter wgpu can see (Vulkan only: the backend Irradiant is tested on).
    pub fn adapters() -> (wgpu::Instance, Vec<Adapter>) {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        if std::env::var_os("WGPU_BACKEND").is_none() {
            desc.backends = Backends::VULKAN;
        }
        // Every indirect dispatch's workgroup counts are written by Irradiant's own shaders,
        // folded under the limits by construction (WORKGROUP_FOLD); wgpu's check of them costs
        // each indirect dispatch a dispatch and a barrier more: 0.011 ms of ddgi/shadow on
        // Sibenik on an H100 (BENCHMARKS.md, commit 88de8bc). WGPU_VALIDATION_INDIRECT_CALL=1
        // turns it back on.
        if std::env::var_os("WGPU_VALIDATION_INDIRECT_CALL").is_none() {
            desc.flags
                .remove(wgpu::InstanceFlags::VALIDATION_INDIRECT_CALL);
        }
        let instance = wgpu::Instance::new(desc);
        let adapters = pollster::block_on(instance.enumerate_adapters(Backends::all()));
        (instance, adapters)
    }

    /// Picks an adapter among [`adapters`](Self::adapters) as `choice` says, checks that
    /// it has the limits, features and formats Irradiant needs, and creates the device.
    pub fn new(choice: &AdapterChoice) -> Result<Self, GpuError> {
        let (instance, adapters) = Self::adapters();
        let names = || {
            adapters
                .iter()
                .enumerate()
                .map(|(i, a)| format!("{i}: {}", a.get_info().name))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let adapter = match choice {
            AdapterChoice::Auto => {
                // Prefer real GPUs over software ones.
                let rank = |a: &Adapter| match a.get_info().device_type {
                    wgpu::DeviceType::DiscreteGpu => 0,
                    wgpu::DeviceType::IntegratedGpu => 1,
                    wgpu::DeviceType::VirtualGpu => 2,
                    wgpu::DeviceType::Other => 3,
                    wgpu::DeviceType::Cpu => 4,
                };
                adapters.iter().min_by_key(|a| rank(a)).cloned()
            }
            AdapterChoice::Index(i) => {
                Some(
                    adapters
                        .get(*i)
                        .cloned()
                        .ok_or_else(|| GpuError::NoMatchingAdapter {
                            wanted: i.to_string(),
                            present: names(),
                        })?,
                )
            }
            AdapterChoice::Name(n) => Some(
                adapters
                    .iter()
                    .find(|a| a.get_info().name.to_lowercase().contains(&n.to_lowercase()))
                    .cloned()
                    .ok_or_else(|| GpuError::NoMatchingAdapter {
                        wanted: n.clone(),
                        present: names(),
                    })?,
            ),
        };
        let adapter = adapter.ok_or_else(|| GpuError::NoAdapter {
            tried: "Vulkan".into(),
        })?;
        Self::from_adapter(instance, adapter)
    }

    /// The features and limits Irradiant needs of `adapter`'s device (a host that creates its
    /// own device asks for at least these): the reason in words where the adapter cannot.
    pub fn requirements(adapter: &Adapter) -> Result<(Features, Limits), GpuError> {
        let available = adapter.limits();
        let unsuitable = |reason| unsuitable(adapter, reason);
        if available.max_storage_textures_per_shader_stage < STORAGE_TEXTURES_NEEDED {
            return Err(unsuitable(format!(
                "it allows {} storage textures per shader stage and Irradiant needs {STORAGE_TEXTURES_NEEDED}",
                available.max_storage_textures_per_shader_stage
            )));
        }
        if available.max_storage_buffers_per_shader_stage < STORAGE_BUFFERS_NEEDED {
            return Err(unsuitable(format!(
                "it allows {} storage buffers per shader stage and Irradiant needs {STORAGE_BUFFERS_NEEDED}",
                available.max_storage_buffers_per_shader_stage
            )));
        }
        // Read-write storage textures of rgba32float (the frame's running means, the path
        // tracer's accumulation) need the adapter's own format capabilities, which every
        // Vulkan adapter has; clearing textures is a Vulkan command too.
        let needed = Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES | Features::CLEAR_TEXTURE;
        if !adapter.features().contains(needed) {
            return Err(unsuitable(format!(
                "it lacks {:?}, which Irradiant needs",
                needed - adapter.features()
            )));
        }
        let read_write = adapter
            .get_texture_format_features(wgpu::TextureFormat::Rgba32Float)
            .flags
            .contains(wgpu::TextureFormatFeatureFlags::STORAGE_READ_WRITE);
        if !read_write {
            return Err(unsuitable(
                "it cannot read and write rgba32float storage textures in one pass".into(),
            ));
        }
        let features = (adapter.features() & Features::TIMESTAMP_QUERY) | needed;
        let limits = Limits {
            max_storage_buffers_per_shader_stage: STORAGE_BUFFERS_NEEDED
                .max(Limits::default().max_storage_buffers_per_shader_stage),
            // Large scenes (Sibenik, Sponza) need big node and triangle buffers.
            max_storage_buffer_binding_size: available.max_storage_buffer_binding_size,
            max_buffer_size: available.max_buffer_size,
            max_texture_array_layers: available.max_texture_array_layers,
            // Large DDGI volumes need wide atlas textures.
            max_texture_dimension_2d: available.max_texture_dimension_2d,
            // frame/gbuffer writes five channels; Vulkan adapters allow far more than 4.
            max_storage_textures_per_shader_stage: STORAGE_TEXTURES_NEEDED
                .max(Limits::default().max_storage_textures_per_shader_stage),
            // A host drawing into Irradiant's G-buffer in one pass (irradiant::host's
            // NativeGBuffer) writes 44 bytes a sample; Vulkan adapters allow 128.
            max_color_attachment_bytes_per_sample: available.max_color_attachment_bytes_per_sample,
            ..Limits::default()
        };
        Ok((features, limits))
    }

    fn from_adapter(instance: wgpu::Instance, adapter: Adapter) -> Result<Self, GpuError> {
        let (features, limits) = Self::requirements(&adapter)?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("irradiant"),
            required_features: features,
            required_limits: limits,
            ..Default::default()
        }))
        .map_err(|e| unsuitable(&adapter, e.to_string()))?;
        let errors = Arc::new(Mutex::new(Vec::new()));
        let out_of_memory = Arc::new(Mutex::new(None));
        let (sink, memory_sink) = (errors.clone(), out_of_memory.clone());
        // wgpu's default handler panics; Irradiant reports errors as values instead.
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| match e {
            wgpu::Error::OutOfMemory { .. } => {
                memory_sink.lock().unwrap().get_or_insert(error_chain(&e));
            }
            _ => sink.lock().unwrap().push(e.to_string()),
        }));
        let lost = Arc::new(Mutex::new(None));
        let lost_sink = lost.clone();
        device.set_device_lost_callback(move |reason, message| {
            *lost_sink.lock().unwrap() = Some(format!("{reason:?}: {message}"));
        });
        Ok(Self {
            info: GpuInfo::of(&adapter, &device),
            instance,
            adapter,
            device,
            queue,
            errors,
            out_of_memory,
            lost,
            passes: Default::default(),
        })
    }

    /// A context on a host's own device and queue (an engine that embeds Irradiant): the
    /// device must have what [`GpuContext::requirements`] lists, or the error names what it
    /// lacks and the fix. The host's error handler and lost-device callback stay the host's:
    /// Irradiant checks what it is handed before wgpu sees it, and [`GpuContext::check`] then
    /// reports only the errors of its own error scopes.
    pub fn from_host(
        instance: wgpu::Instance,
        adapter: Adapter,
        device: Device,
        queue: Queue,
    ) -> Result<Self, GpuError> {
        let (features, limits) = Self::requirements(&adapter)?;
        let unsuitable = |reason| unsuitable(&adapter, reason);
        let missing = features - device.features();
        if !missing.is_empty() {
            return Err(unsuitable(format!(
                "the host's device was created without {missing:?}: request the features GpuContext::requirements lists"
            )));
        }
        let have = device.limits();
        for (name, needed, got) in [
            (
                "max_storage_buffers_per_shader_stage",
                limits.max_storage_buffers_per_shader_stage,
                have.max_storage_buffers_per_shader_stage,
            ),
            (
                "max_storage_textures_per_shader_stage",
                limits.max_storage_textures_per_shader_stage,
                have.max_storage_textures_per_shader_stage,
            ),
        ] {
            if got < needed {
                return Err(unsuitable(format!(
                    "the host's device allows {got} for limit {name} and Irradiant needs {needed}: request the limits GpuContext::requirements lists"
                )));
            }
        }
        Ok(Self {
            info: GpuInfo::of(&adapter, &device),
            instance,
            adapter,
            device,
            queue,
            errors: Default::default(),
            out_of_memory: Default::default(),
            passes: Default::default(),
            lost: Default::default(),
        })
    }

    /// Why the device was lost, if it was (the viewer then offers a restart on a new one).
    pub fn lost(&self) -> Option<String> {
        self.lost.lock().unwrap().clone()
    }

    /// Reports the first error the device raised since the last check, or its loss.
    pub fn check(&self, what: &str) -> Result<(), GpuError> {
        if let Some(reason) = self.lost.lock().unwrap().clone() {
            return Err(GpuError::DeviceLost(reason));
        }
        self.check_memory(what)?;
        let mut errors = self.errors.lock().unwrap();
        if let Some(message) = errors.first().cloned() {
            errors.clear();
            return Err(GpuError::Validation {
                what: what.to_owned(),
                message,
            });
        }
        Ok(())
    }

    /// Blocks until the GPU has finished all submitted work.
    pub fn wait(&self) -> Result<(), GpuError> {
        self.wait_until(None)?;
        self.check("GPU work")
    }

    /// Blocks until the GPU has finished the submission `index` (and all before it).
    pub fn wait_for(&self, index: wgpu::SubmissionIndex) -> Result<(), GpuError> {
        self.wait_until(Some(index))
    }

    fn wait_until(&self, submission_index: Option<wgpu::SubmissionIndex>) -> Result<(), GpuError> {
        self.device
            .poll(wgpu::PollType::Wait {
                submission_index,
                timeout: None,
            })
            .map(|_| ())
            .map_err(|e| GpuError::Poll(e.to_string()))
    }

    /// Checks that `allocations` fit this adapter (see [`crate::Budget`]).
    pub fn check_allocations(&self, allocations: &[crate::Allocation]) -> Result<(), GpuError> {
        crate::Budget::of(self).check(allocations)
    }

    /// A uniform buffer holding `value`, labelled `label` (it may be written again). A
    /// dispatch whose values differ from the others' in one encoder needs its own: a queue
    /// write lands before the whole submission, not before the dispatch that follows it.
    pub fn uniform_buffer<T: bytemuck::Pod>(&self, label: &str, value: &T) -> wgpu::Buffer {
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: size_of::<T>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.queue
            .write_buffer(&buffer, 0, bytemuck::bytes_of(value));
        buffer
    }

    /// An out-of-memory error the device raised since the last check, as an error; taken.
    fn check_memory(&self, what: &str) -> Result<(), GpuError> {
        match self.out_of_memory.lock().unwrap().take() {
            Some(message) => {
                // What failed after it is its consequence.
                self.errors.lock().unwrap().clear();
                Err(GpuError::OutOfMemory {
                    what: what.to_owned(),
                    message,
                })
            }
            None => Ok(()),
        }
    }

    /// Runs `build` inside validation and out-of-memory error scopes, turning errors into
    /// values; an earlier out-of-memory error comes first (it is the cause).
    pub fn scoped<T>(&self, what: &str, build: impl FnOnce(&Device) -> T) -> Result<T, GpuError> {
        let memory = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let value = build(&self.device);
        let validation = pollster::block_on(validation.pop());
        if let Some(e) = pollster::block_on(memory.pop()) {
            return Err(GpuError::OutOfMemory {
                what: what.to_owned(),
                message: error_chain(&e),
            });
        }
        self.check_memory(what)?;
        match validation {
            Some(e) => Err(GpuError::Validation {
                what: what.to_owned(),
                message: e.to_string(),
            }),
            None => Ok(value),
        }
    }
}

/// An error and its sources on one line (wgpu's own text of an out-of-memory error is only
/// "Out of Memory"; its source says what was being made).
fn error_chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        text.push_str(": ");
        text.push_str(&s.to_string());
        source = s.source();
    }
    text
}

/// The largest device-local memory heap of a Vulkan adapter (wgpu has no portable query).
fn device_local_memory(adapter: &Adapter) -> Option<u64> {
    // SAFETY: only reads the physical device's memory properties; nothing is created or
    // destroyed through the hal handles, which outlive this call.
    unsafe {
        let hal = adapter.as_hal::<wgpu::hal::api::Vulkan>()?;
        let instance = hal.shared_instance().raw_instance();
        let properties = instance.get_physical_device_memory_properties(hal.raw_physical_device());
        properties.memory_heaps[..properties.memory_heap_count as usize]
            .iter()
            .filter(|h| h.flags.contains(ash::vk::MemoryHeapFlags::DEVICE_LOCAL))
            .map(|h| h.size)
            .max()
    }
}

/// The error of an adapter (or a device on it) that cannot serve Irradiant, and why.
fn unsuitable(adapter: &Adapter, reason: String) -> GpuError {
    GpuError::Unsuitable {
        adapter: adapter.get_info().name,
        reason,
    }
}

/// The machine's physical memory (Linux: MemTotal of /proc/meminfo).
fn system_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

impl GpuInfo {
    /// The description and limits of `adapter` and the `device` made on it.
    fn of(adapter: &Adapter, device: &Device) -> Self {
        let info = adapter.get_info();
        let device_limits = device.limits();
        GpuInfo {
            name: info.name.clone(),
            backend: format!("{:?}", info.backend),
            device_type: format!("{:?}", info.device_type),
            driver: info.driver.clone(),
            driver_info: info.driver_info.clone(),
            timestamps: device.features().contains(Features::TIMESTAMP_QUERY),
            loop_iteration_limit: info
                .name
                .contains("llvmpipe")
                .then_some(LLVMPIPE_LOOP_ITERATIONS),
            max_storage_buffer_binding_size: device_limits.max_storage_buffer_binding_size,
            max_buffer_size: device_limits.max_buffer_size,
            max_compute_workgroup_size_x: device_limits.max_compute_workgroup_size_x,
            max_storage_buffers_per_shader_stage: device_limits
                .max_storage_buffers_per_shader_stage,
            max_compute_workgroups_per_dimension: device_limits
                .max_compute_workgroups_per_dimension,
            memory: if info.device_type == wgpu::DeviceType::Cpu {
                // A software adapter's memory is the machine's; the heap it reports is nominal
                // (lavapipe reports 2 GiB and allocates far more).
                system_memory()
            } else {
                device_local_memory(adapter)
            },
        }
    }
}

/// The ICD file of Mesa's lavapipe (Vulkan on the CPU), where it is installed: setting
/// `VK_ICD_FILENAMES` to it pins a process to that device, as the window tests under Xvfb do
/// (Xvfb has no DRI3, which hardware drivers need to present).
pub fn lavapipe_icd() -> Option<std::path::PathBuf> {
    std::fs::read_dir("/usr/share/vulkan/icd.d")
        .ok()?
        .flatten()
        .map(|entry| entry.path())
        .find(|path| path.to_string_lossy().contains("lvp_icd"))
}
