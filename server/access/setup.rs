//! Deciding the access mode at start-up: `--open` (development, loopback only) or the
//! operator and dialog-manager credentials from the environment, else `docent.yaml`, else
//! generated for this run. A server reachable from the network needs a credential the site
//! chose (a generated one changes with every start and is only printed on the console).

use crate::access::{AccessMode, Credentials, Secret};
use crate::content::config::{AccessSettings, Credential};

/// The environment variable holding the operator credential.
pub const OPERATOR_TOKEN_ENV: &str = "DOCENT_OPERATOR_TOKEN";
/// The environment variable holding the dialog-manager credential.
pub const DM_TOKEN_ENV: &str = "DOCENT_DM_TOKEN";

/// Where a credential came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// An environment variable.
    Environment,
    /// `docent.yaml`.
    Settings,
    /// Generated for this run.
    Generated,
}

/// The decided access mode, with where each credential came from.
#[derive(Debug)]
pub struct AccessSetup {
    /// What the server enforces.
    pub mode: AccessMode,
    /// The operator credential's origin (`None` when open).
    pub operator: Option<Origin>,
    /// The dialog-manager credential's origin (`None` when open).
    pub dm: Option<Origin>,
}

/// Why the server must not start.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum SetupError {
    /// `--open` on an address other machines can reach.
    #[error(
        "--open is for development on this machine only: it cannot be used with a \
         non-loopback --listen address"
    )]
    OpenOnNetwork,
    /// A network address without a chosen operator credential.
    #[error(
        "listening on a network address needs an operator credential: set {OPERATOR_TOKEN_ENV} \
         (at least 16 characters) or `access: operator_token:` in docent.yaml"
    )]
    NoCredential,
    /// The operator and dialog-manager credentials are the same, so neither role is told
    /// apart (a dialog manager would have operator powers).
    #[error(
        "the operator and dialog-manager credentials must differ: a dialog manager would \
         otherwise have the operator's powers"
    )]
    SameCredential,
    /// An environment variable holds an unusable credential.
    #[error("{0} is not usable as a credential: {1}")]
    Weak(&'static str, crate::content::config::WeakCredential),
}

/// Decides the access mode. `env` reads an environment variable (tests pass their own).
pub fn decide_access(
    open: bool,
    loopback: bool,
    settings: &AccessSettings,
    env: impl Fn(&str) -> Option<String>,
) -> Result<AccessSetup, SetupError> {
    if open {
        if !loopback {
            return Err(SetupError::OpenOnNetwork);
        }
        return Ok(AccessSetup {
            mode: AccessMode::Open,
            operator: None,
            dm: None,
        });
    }
    let (operator, operator_origin) =
        credential(OPERATOR_TOKEN_ENV, settings.operator_token.as_ref(), &env)?;
    let (dm, dm_origin) = credential(DM_TOKEN_ENV, settings.dm_token.as_ref(), &env)?;
    if !loopback && operator_origin == Origin::Generated {
        return Err(SetupError::NoCredential);
    }
    if operator.matches(dm.expose()) {
        return Err(SetupError::SameCredential);
    }
    Ok(AccessSetup {
        mode: AccessMode::Guarded(Credentials { operator, dm }),
        operator: Some(operator_origin),
        dm: Some(dm_origin),
    })
}

fn credential(
    var: &'static str,
    configured: Option<&Credential>,
    env: &impl Fn(&str) -> Option<String>,
) -> Result<(Secret, Origin), SetupError> {
    if let Some(value) = env(var).filter(|v| !v.is_empty()) {
        let checked = Credential::new(value).map_err(|e| SetupError::Weak(var, e))?;
        return Ok((Secret::new(checked.expose()), Origin::Environment));
    }
    if let Some(configured) = configured {
        return Ok((Secret::new(configured.expose()), Origin::Settings));
    }
    Ok((Secret::generate(), Origin::Generated))
}

#[cfg(test)]
mod tests {
    use super::*;

    const OP: &str = "operator-secret-0123";
    const DM: &str = "dialog-manager-0123";

    fn settings() -> AccessSettings {
        AccessSettings {
            operator_token: Some(Credential::new("from-the-settings-1").expect("strong")),
            dm_token: None,
        }
    }

    fn env(var: &str) -> Option<String> {
        match var {
            OPERATOR_TOKEN_ENV => Some(OP.into()),
            DM_TOKEN_ENV => Some(DM.into()),
            _ => None,
        }
    }

    fn no_env(_: &str) -> Option<String> {
        None
    }

    fn credentials(setup: &AccessSetup) -> &Credentials {
        match &setup.mode {
            AccessMode::Guarded(c) => c,
            AccessMode::Open => panic!("open"),
        }
    }

    #[test]
    fn the_environment_wins_over_the_settings() {
        let setup = decide_access(false, false, &settings(), env).expect("starts");
        assert!(credentials(&setup).operator.matches(OP));
        assert!(credentials(&setup).dm.matches(DM));
        assert_eq!(setup.operator, Some(Origin::Environment));
    }

    #[test]
    fn settings_then_generated_credentials_fill_the_gaps() {
        let setup = decide_access(false, true, &settings(), no_env).expect("starts");
        assert!(credentials(&setup).operator.matches("from-the-settings-1"));
        assert_eq!(setup.operator, Some(Origin::Settings));
        assert_eq!(setup.dm, Some(Origin::Generated));
        assert_eq!(credentials(&setup).dm.expose().len(), 32);
    }

    #[test]
    fn a_network_address_needs_a_chosen_operator_credential() {
        let none = AccessSettings::default();
        assert_eq!(
            decide_access(false, false, &none, no_env).unwrap_err(),
            SetupError::NoCredential
        );
        assert!(decide_access(false, true, &none, no_env).is_ok());
        assert!(decide_access(false, false, &settings(), no_env).is_ok());
    }

    #[test]
    fn open_is_refused_on_a_network_address() {
        let none = AccessSettings::default();
        assert_eq!(
            decide_access(true, false, &none, no_env).unwrap_err(),
            SetupError::OpenOnNetwork
        );
        let setup = decide_access(true, true, &none, env).expect("starts");
        assert!(matches!(setup.mode, AccessMode::Open));
    }

    #[test]
    fn the_two_roles_need_different_credentials() {
        let same = |_: &str| Some(OP.to_owned());
        let error = decide_access(false, true, &AccessSettings::default(), same).unwrap_err();
        assert_eq!(error, SetupError::SameCredential);
    }

    #[test]
    fn a_weak_credential_in_the_environment_is_refused() {
        let weak = |var: &str| (var == OPERATOR_TOKEN_ENV).then(|| "short".to_owned());
        let error = decide_access(false, true, &settings(), weak).unwrap_err();
        assert!(matches!(error, SetupError::Weak(OPERATOR_TOKEN_ENV, _)));
        assert!(!error.to_string().contains("short"));
    }
}
