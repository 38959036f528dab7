//! The bar a bake draws on the terminal. (Where bakes and references are cached is the
//! library's rule: irradiant::pathtrace::reference_cache::cache_dir.)

use std::sync::{Arc, Mutex};

use indicatif::{ProgressBar, ProgressStyle};
use irradiant::technique::Progress;

/// A progress bar on stderr for bakes (hidden where stderr is not a terminal).
pub fn bake_progress() -> Progress {
    let bar: Mutex<Option<ProgressBar>> = Mutex::new(None);
    Progress(Arc::new(move |what: &str, done: u32, all: u32| {
        let mut bar = bar.lock().unwrap_or_else(|e| e.into_inner());
        let b = bar.get_or_insert_with(|| {
            let b = ProgressBar::new(all as u64);
            b.set_style(
                ProgressStyle::with_template(
                    "{spinner} {msg} [{elapsed_precise} < {eta}] {wide_bar} {pos}/{len}",
                )
                .expect("a valid progress template"),
            );
            b
        });
        b.set_message(what.to_owned());
        b.set_position(done as u64);
        if done >= all {
            b.finish_and_clear();
            *bar = None;
        }
    }))
}
