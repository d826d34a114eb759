//! `sdfc view`'s window and what it shows: the application (`app`, its keys in `keys`, its
//! window events in `window`), the live picture (`live`) with its orbit camera (`orbit`)
//! drawn to the window (`present`), the data form's moments while `time` runs (`moments`), the file watcher (`watch`, also `--watch` of `render` and
//! `emit`) and the scripted input (`script`).

mod app;
mod keys;
mod live;
mod moments;
mod orbit;
mod present;
pub mod script;
pub mod watch;
mod window;

pub use app::{App, load};
