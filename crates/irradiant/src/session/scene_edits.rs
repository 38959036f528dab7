//! What a host (or a tool) changes in the scene between frames: instances added, moved and
//! removed, lights moved or recoloured, the sky. Each change is checked first and refused by
//! name; each reaches the GPU scene and the technique as an animation's would.

use glam::{Mat4, Vec3};
use irradiant_scene::{Instance, Light, LightKind, Material, Mesh};

use super::Session;
use crate::RenderError;
use crate::frame::{LightingChange, SceneChange};
use crate::scene::GpuScene;

impl Session {
    /// The ids of the scene's instances, in the scene's order ([`Session::scene`]`.instances`):
    /// an instance loaded with the scene keeps its index there as its id, one added by
    /// [`Session::add_instance`] the id it returned.
    pub fn instance_ids(&self) -> &[usize] {
        &self.instance_ids
    }

    /// Moves instance `id` ([`Session::instance_ids`]) to `transform` from the next frame,
    /// over what the scene's animation says; the technique is told as of any moving instance,
    /// and the instance counts as moving from then on (DDGI wakes the probes around it). A
    /// host moves its objects so. An unknown id, or a transform that is not finite or not
    /// invertible, is refused by name.
    pub fn set_instance_transform(
        &mut self,
        id: usize,
        transform: Mat4,
    ) -> Result<(), RenderError> {
        let index = self.instance_index(id)?;
        check_transform(&format!("instance {id}'s transform"), &transform)?;
        self.moved[index] = Some(transform);
        self.gpu_scene.set_moving(index);
        self.repose(Vec::new());
        Ok(())
    }

    /// Places a new instance of mesh `mesh` (an index into the scene's meshes: a host
    /// registers every mesh in the scene it starts the session with) at `transform` from the
    /// next frame, and returns its id. It counts as moving: DDGI wakes the probes around it.
    /// `name` is how animations address it (empty: `instance-<id>`). Within
    /// [`crate::GpuSceneSettings::instance_headroom`] this costs an upload of the top-level
    /// tree; past it the scene's buffers, the frame and the technique are built anew, larger
    /// (the probes start again).
    pub fn add_instance(
        &mut self,
        mesh: u32,
        transform: Mat4,
        name: &str,
    ) -> Result<usize, RenderError> {
        let meshes = self.scene.meshes.len();
        if mesh as usize >= meshes {
            return Err(RenderError::Settings(format!(
                "mesh {mesh} does not exist: the scene has {meshes} meshes; register every mesh in the scene the session starts with"
            )));
        }
        let id = self.next_instance_id;
        let name = if name.is_empty() {
            format!("instance-{id}")
        } else {
            name.to_owned()
        };
        check_transform(&format!("instance {name:?}'s transform"), &transform)?;
        if self.scene.instances.iter().any(|i| i.name == name) {
            return Err(RenderError::Settings(format!(
                "an instance named {name:?} exists already: give each instance its own name (animations address instances by name)"
            )));
        }
        self.scene.instances.push(Instance {
            name,
            mesh,
            transform,
        });
        if self.gpu_scene.has_room_for(mesh) {
            self.gpu_scene.add_instance(mesh);
        } else if let Err(error) = self.rebuild_scene(true) {
            self.scene.instances.pop();
            return Err(error);
        }
        self.next_instance_id += 1;
        self.instance_ids.push(id);
        self.moved.push(Some(transform));
        self.repose(Vec::new());
        Ok(id)
    }

    /// Registers a mesh while running, with its own `materials` (its triangle materials index
    /// them, from 0), and returns its index for [`Session::add_instance`]. Checked as a loaded
    /// file is: a vertex that is not finite or an index or material out of range is refused
    /// naming the mesh. Costly: every mesh's tree, the scene's buffers, the frame and the
    /// technique are built anew (the probes start again): register meshes up front where you
    /// can. A material's texture must be one the scene has.
    pub fn add_mesh(
        &mut self,
        mut mesh: Mesh,
        materials: Vec<Material>,
    ) -> Result<u32, RenderError> {
        let textures = self.scene.textures.len();
        if let Some(m) = materials
            .iter()
            .find(|m| m.base_color_texture.is_some_and(|t| t as usize >= textures))
        {
            return Err(RenderError::Settings(format!(
                "material '{}' of mesh '{}' uses a texture the scene lacks (it has {textures}): give the session's scene every texture at the start",
                m.name, mesh.name
            )));
        }
        let first_material = self.scene.materials.len() as u32;
        for m in &mut mesh.triangle_materials {
            // Past the new materials stays past them: validation names it.
            *m = m.saturating_add(first_material);
        }
        let mut scene = self.scene.clone();
        scene.meshes.push(mesh);
        scene.materials.extend(materials);
        let mut warnings = Vec::new();
        irradiant_scene::validate(&mut scene, super::HOST_SCENE.as_ref(), &mut warnings)
            .map_err(|e| RenderError::Settings(e.to_string()))?;
        let previous = std::mem::replace(&mut self.scene, scene);
        if let Err(error) = self.rebuild_scene(false) {
            self.scene = previous;
            return Err(error);
        }
        self.warnings.extend(warnings);
        Ok(self.scene.meshes.len() as u32 - 1)
    }

    /// Removes instance `id` from the next frame; DDGI wakes the probes where it stood. The
    /// other instances keep their ids. The last instance cannot be removed (move it away).
    pub fn remove_instance(&mut self, id: usize) -> Result<(), RenderError> {
        let index = self.instance_index(id)?;
        if self.scene.instances.len() == 1 {
            return Err(RenderError::Settings(format!(
                "instance {id} is the scene's last: a scene keeps at least one instance; move it out of view instead"
            )));
        }
        self.scene.instances.remove(index);
        self.moved.remove(index);
        self.instance_ids.remove(index);
        let vacated = self.gpu_scene.remove_instance(index);
        self.repose(vacated.into_iter().collect());
        Ok(())
    }

    /// Replaces light `index` (in the scene's lights' order) from the next frame: moved,
    /// turned, recoloured or of another kind (an animation still applies over it). The
    /// technique is told as of any light change. A light that is not finite, has a negative
    /// intensity or colour, or no direction where its kind needs one, is refused by name.
    pub fn set_light(&mut self, index: usize, light: Light) -> Result<(), RenderError> {
        let count = self.scene.lights.len();
        if index >= count {
            return Err(RenderError::Settings(format!(
                "light {index} does not exist: the scene has {count} lights; start the session with every light the host will use (switch the unused ones off)"
            )));
        }
        let name = &light.name;
        let finite = light.position.is_finite()
            && light.direction.is_finite()
            && light.color.is_finite()
            && light.intensity.is_finite();
        if !finite || light.intensity < 0.0 || light.color.min_element() < 0.0 {
            return Err(RenderError::Settings(format!(
                "light {index} ({name:?}) is not finite or negative: give a finite position and direction and a colour and intensity of at least 0"
            )));
        }
        let directed = !matches!(light.kind, LightKind::Point);
        if directed && light.direction.length_squared() < 1e-12 {
            return Err(RenderError::Settings(format!(
                "light {index} ({name:?}) has no direction: a spot or directional light needs a non-zero direction"
            )));
        }
        self.scene.lights[index] = light;
        self.repose(Vec::new());
        Ok(())
    }

    /// Changes the radiance of rays that leave the scene (linear RGB) from the next frame;
    /// the technique is told as of a large light change. A negative or non-finite sky is
    /// refused.
    pub fn set_sky(&mut self, sky: Vec3) -> Result<(), RenderError> {
        if !sky.is_finite() || sky.min_element() < 0.0 {
            return Err(RenderError::Settings(format!(
                "the sky {sky} is not a radiance: give finite components of at least 0"
            )));
        }
        if sky == self.scene.sky {
            return Ok(());
        }
        self.scene.sky = sky;
        self.gpu_scene.sky = sky;
        self.gpu_scene.update(&self.ctx, &self.pose);
        self.frame.restart_direct();
        self.technique.scene_changed(&SceneChange {
            lighting: LightingChange::Large,
            geometry: false,
            dynamic_bounds: self.gpu_scene.dynamic_bounds(),
        });
        Ok(())
    }

    /// Where instance `id` is in the scene's order.
    fn instance_index(&self, id: usize) -> Result<usize, RenderError> {
        self.instance_ids
            .iter()
            .position(|&i| i == id)
            .ok_or_else(|| {
                RenderError::Settings(format!(
                    "instance {id} does not exist: the ids in use are {:?} (Session::instance_ids)",
                    self.instance_ids
                ))
            })
    }

    /// Builds the scene's buffers anew with twice the room for added instances, and the frame
    /// and the technique over them: what adding past the headroom, or a mesh, costs.
    /// `instance_added`: the scene's last instance was just pushed (placed by hand).
    fn rebuild_scene(&mut self, instance_added: bool) -> Result<(), RenderError> {
        self.ctx.wait()?;
        self.in_flight.clear();
        let mut settings = self.scene_settings.clone();
        settings.instance_headroom = (settings.instance_headroom * 2).max(16);
        let mut gpu_scene = GpuScene::new(&self.ctx, &self.scene, &settings)?;
        for (index, moved) in self.moved.iter().enumerate() {
            if moved.is_some() {
                gpu_scene.set_moving(index);
            }
        }
        if instance_added {
            // The instance just pushed (past `moved`) is placed by hand too.
            gpu_scene.set_moving(self.scene.instances.len() - 1);
        }
        let frame = crate::frame::Frame::new(
            &self.ctx,
            &gpu_scene,
            self.frame.size(),
            self.frame.settings().clone(),
            self.frame.resources.needs,
        )?;
        self.gpu_scene = gpu_scene;
        self.frame = frame;
        let kind = self.spec.kind()?;
        self.technique = self.build_technique(kind, &self.spec)?;
        self.scene_settings = settings;
        self.tell_pose();
        Ok(())
    }
}

/// Refuses a transform that is not finite or flattens the object.
fn check_transform(what: &str, transform: &Mat4) -> Result<(), RenderError> {
    let determinant = transform.determinant();
    if !transform.is_finite() || !determinant.is_finite() || determinant.abs() < 1e-12 {
        return Err(RenderError::Settings(format!(
            "{what} {transform:?} is not finite or not invertible: give a finite transform that does not flatten the object"
        )));
    }
    Ok(())
}
