//! Docent's integration tests, one binary (each file below was a binary of its own; linking
//! the whole crate 60 times cost more than running the tests). They start real servers on
//! 127.0.0.1:0, real processes of the `docent` binary, real brokers and real readers; every
//! wait is for an event. `tests/flood.rs` is apart: it measures the memory of its process;
//! so is `tests/soak.rs`, a minute of compressed load measuring the server's (`bench/soak.sh`).

mod common;
mod fleet_support;
#[path = "ros/harness.rs"]
mod ros;

mod access;
mod architecture_map;
mod browser_shells;
mod bundle_files;
mod channel_policies;
mod cli;
mod cli_explain;
mod clock_jumps;
mod consent_under_load;
mod corpus_annotations;
mod corpus_cli;
mod corpus_export;
mod corpus_faults;
mod corpus_kill;
mod corpus_log;
mod corpus_recording;
mod corpus_robot_events;
mod corpus_sessions;
mod corpus_touches;
mod corpus_unwritable;
mod crate_graph;
mod dispatch_sequencing;
mod dm_example;
mod documented_limits;
mod fleet_broker_restart;
mod fleet_flood;
mod fleet_mqtt;
mod fleet_stop;
mod fleet_tls;
mod forwarded_for;
mod highlight;
mod http_api;
mod http_limits;
mod kiosk_lost;
mod languages;
mod live_reload;
mod live_reload_flood;
mod media_conversion;
mod operator_protocol;
mod projector_video;
mod recording_alarms;
mod recording_limits;
mod report;
mod robot_reactions;
mod rosbridge_drive;
mod rosbridge_events;
mod schema;
mod server_limits;
mod slow_client;
mod speech_espeak;
mod staff_mistakes;
mod touchscreen_reports;
mod translations;
mod translations_refusals;
mod translations_rows;
mod translations_sheets;
mod ws_adapter;
mod ws_backpressure;
mod ws_close_codes;
mod ws_limits;
mod ws_protocol;
