//! Verb → adapter. Built once from the site configuration; the only place that knows which
//! adapter serves which verb.

use std::collections::HashMap;
use std::sync::Arc;

use crate::adapters::{
    Adapter, DisplayAdapter, DisplayState, DriveSim, ExternalAdapters, RosbridgeDrive,
    SpeechOutput, espeak_adapter, log_adapter,
};
use crate::content::Verb;
use crate::content::config::{AdapterKind, SiteConfig};
use crate::events::Hub;
use crate::lifecycle::Lifecycle;
use crate::robot::RobotInbox;

/// The adapters a server runs, as handles other parts read state from; the [`Router`] that
/// reaches them goes to the dispatcher alone.
pub struct Devices {
    /// Touchscreen and projector state.
    pub display: Arc<DisplayState>,
    /// The simulated base, when the drive is simulated.
    pub drive: Option<Arc<DriveSim>>,
    /// The ROS 2 robot's link and drive, when `rosbridge:` has a `url`.
    pub rosbridge: Option<Arc<RosbridgeDrive>>,
    /// External adapter connections.
    pub external: Arc<ExternalAdapters>,
    /// The speech adapter actually used (`espeak`, `log`, `ws` or `browser`).
    pub speech: AdapterKind,
    /// The name of the adapter that carries out `SAY` (`browser` speech runs as `ws`).
    pub speech_adapter: &'static str,
    /// Where adapters that hear the robot's own sensors hand in robot events.
    pub robot_inbox: RobotInbox,
}

impl Devices {
    /// Starts every adapter the configuration routes to. `speech` is the speech adapter to use,
    /// already decided by the caller (which knows whether espeak-ng is installed); `home` is the
    /// page the kiosk starts on, if the bundle has it.
    pub fn start(
        config: &SiteConfig,
        home: Option<String>,
        speech: AdapterKind,
        speech_output: SpeechOutput,
        (hub, robot_inbox): (&Hub, &RobotInbox),
        life: &Lifecycle,
    ) -> (Devices, Router) {
        let display = DisplayState::start(home, config.adapter_timeout, hub.clone(), life);
        let external = Arc::new(ExternalAdapters::new(
            config.adapter_timeout,
            config.speech.rate_wpm,
            life.clone(),
        ));
        let log = Arc::new(log_adapter(config.speech.rate_wpm, life));
        let drive = (config.drive.adapter == AdapterKind::DriveSim)
            .then(|| Arc::new(DriveSim::new(&config.drive, hub.clone(), life)));
        let ros = &config.rosbridge;
        let rosbridge = ros.url.clone().map(|url| {
            let inbox = robot_inbox.clone();
            Arc::new(RosbridgeDrive::start(ros, url, hub.clone(), inbox, life))
        });
        let display_adapter: Arc<dyn Adapter> = Arc::new(DisplayAdapter::new(Arc::clone(&display)));
        let espeak: Option<Arc<dyn Adapter>> = (speech == AdapterKind::Espeak).then(|| {
            let s = &config.speech;
            Arc::new(espeak_adapter(
                s.voice.clone(),
                s.voices.clone(),
                s.rate_wpm,
                speech_output,
                life,
            )) as _
        });
        let pick = |kind: AdapterKind| -> Arc<dyn Adapter> {
            match kind {
                AdapterKind::Espeak => espeak.clone().unwrap_or_else(|| log.clone()),
                AdapterKind::Log => log.clone(),
                // The kiosk shell serves browser speech as a websocket adapter.
                AdapterKind::Ws | AdapterKind::Browser => external.clone(),
                AdapterKind::Display => display_adapter.clone(),
                AdapterKind::DriveSim => match &drive {
                    Some(d) => d.clone(),
                    None => log.clone(),
                },
                // The config check refuses a rosbridge drive without a `url`.
                AdapterKind::Rosbridge => match &rosbridge {
                    Some(r) => r.clone(),
                    None => log.clone(),
                },
            }
        };
        let mut routes: HashMap<Verb, Arc<dyn Adapter>> = HashMap::new();
        routes.insert(Verb::Say, pick(speech));
        for verb in [Verb::DisplayPage, Verb::Project, Verb::Highlight] {
            routes.insert(verb, pick(config.display.adapter));
        }
        for verb in [Verb::SetWaypoint, Verb::DriveStart, Verb::DriveStop] {
            routes.insert(verb, pick(config.drive.adapter));
        }
        for (name, site) in &config.verbs {
            routes.insert(Verb::Site(name.as_str().into()), pick(site.adapter));
        }
        let speech_adapter = pick(speech).name();
        (
            Devices {
                display,
                drive,
                rosbridge,
                external,
                speech,
                speech_adapter,
                robot_inbox: robot_inbox.clone(),
            },
            Router::new(routes),
        )
    }
}

/// Which adapter serves each verb.
pub struct Router {
    routes: HashMap<Verb, Arc<dyn Adapter>>,
    distinct: Vec<Arc<dyn Adapter>>,
}

impl Router {
    /// A router over these routes.
    pub fn new(routes: HashMap<Verb, Arc<dyn Adapter>>) -> Self {
        let mut distinct: Vec<Arc<dyn Adapter>> = Vec::new();
        for adapter in routes.values() {
            if !distinct.iter().any(|d| Arc::ptr_eq(d, adapter)) {
                distinct.push(Arc::clone(adapter));
            }
        }
        distinct.sort_by_key(|a| a.name());
        Router { routes, distinct }
    }

    /// The adapter for `verb`; `None` for `WAIT` (the dispatcher's own) and undeclared verbs.
    pub fn adapter_for(&self, verb: &Verb) -> Option<&Arc<dyn Adapter>> {
        self.routes.get(verb)
    }

    /// Every adapter once, by name.
    pub fn adapters(&self) -> &[Arc<dyn Adapter>] {
        &self.distinct
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::content::config::{ArgRule, SiteVerb};

    fn names(router: &Router, verbs: &[Verb]) -> Vec<&'static str> {
        verbs
            .iter()
            .map(|v| router.adapter_for(v).map_or("none", |a| a.name()))
            .collect()
    }

    #[tokio::test]
    async fn defaults_need_no_hardware() {
        let (hub, _rx) = Hub::new();
        let (_, router) = Devices::start(
            &SiteConfig::default(),
            None,
            AdapterKind::Log,
            SpeechOutput::Audio,
            (&hub, &RobotInbox::channel().0),
            &Lifecycle::new(),
        );
        let verbs = [
            Verb::Say,
            Verb::DisplayPage,
            Verb::Project,
            Verb::Highlight,
            Verb::SetWaypoint,
            Verb::DriveStart,
            Verb::DriveStop,
            Verb::Wait,
        ];
        assert_eq!(
            names(&router, &verbs),
            [
                "log", "display", "display", "display", "sim", "sim", "sim", "none"
            ]
        );
        let all: Vec<&str> = router.adapters().iter().map(|a| a.name()).collect();
        assert_eq!(all, ["display", "log", "sim"]);
    }

    #[tokio::test]
    async fn the_configuration_routes_built_in_and_site_verbs() {
        let mut config = SiteConfig::default();
        config.display.adapter = AdapterKind::Ws;
        config.drive.adapter = AdapterKind::Ws;
        for (name, adapter) in [("LIGHTS", AdapterKind::Log), ("ARM", AdapterKind::Ws)] {
            let verb = SiteVerb {
                adapter,
                argument: ArgRule::Optional,
                description: None,
            };
            config.verbs.insert(name.to_owned(), verb);
        }
        let (hub, _rx) = Hub::new();
        let (devices, router) = Devices::start(
            &config,
            None,
            AdapterKind::Ws,
            SpeechOutput::Audio,
            (&hub, &RobotInbox::channel().0),
            &Lifecycle::new(),
        );
        let verbs = [
            Verb::Say,
            Verb::Project,
            Verb::Highlight,
            Verb::DriveStop,
            Verb::Site("LIGHTS".into()),
            Verb::Site("ARM".into()),
            Verb::Site("NOPE".into()),
        ];
        assert_eq!(
            names(&router, &verbs),
            ["ws", "ws", "ws", "ws", "log", "ws", "none"]
        );
        assert!(
            devices.drive.is_none(),
            "no simulated base when the drive is external"
        );
        let all: Vec<&str> = router.adapters().iter().map(|a| a.name()).collect();
        assert_eq!(all, ["log", "ws"], "each adapter once");
    }
}
