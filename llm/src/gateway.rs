//! One bounded gateway per model server, shared by every scene in the process: at most
//! `max_in_flight` requests at once and, optionally, at most `rate_per_s` started per second, so a
//! thousand scenes never open a thousand connections.

use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use tokio::sync::{Mutex, OwnedSemaphorePermit, Semaphore};
use tokio::time::Instant;

use std::collections::BTreeMap;

use crate::ModelConfig;

/// A bounded queue in front of one model server.
#[derive(Debug)]
pub struct ModelGateway {
    name: String,
    slots: Arc<Semaphore>,
    in_flight: Arc<AtomicUsize>,
    peak: Arc<AtomicUsize>,
    interval: Option<Duration>,
    next_start: Mutex<Instant>,
}

/// A place in flight; the place is given back when this is dropped.
#[derive(Debug)]
pub struct Permit {
    _slot: OwnedSemaphorePermit,
    in_flight: Arc<AtomicUsize>,
}

impl Drop for Permit {
    fn drop(&mut self) {
        self.in_flight.fetch_sub(1, Ordering::SeqCst);
    }
}

impl ModelGateway {
    /// A gateway letting `max_in_flight` requests through at once, `rate_per_s` per second at most.
    pub fn new(name: impl Into<String>, max_in_flight: usize, rate_per_s: Option<f64>) -> Self {
        let interval = rate_per_s
            .filter(|r| r.is_finite() && *r > 0.0)
            .map(|r| Duration::from_secs_f64(1.0 / r));
        ModelGateway {
            name: name.into(),
            slots: Arc::new(Semaphore::new(max_in_flight.max(1))),
            in_flight: Arc::new(AtomicUsize::new(0)),
            peak: Arc::new(AtomicUsize::new(0)),
            interval,
            next_start: Mutex::new(Instant::now()),
        }
    }

    /// The server's name in the config.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Waits for a place in flight (and for the rate limit), then holds it until the permit drops.
    pub async fn acquire(&self) -> Permit {
        let slot = Arc::clone(&self.slots)
            .acquire_owned()
            .await
            .expect("the gateway's semaphore is never closed");
        if let Some(interval) = self.interval {
            let start = {
                let mut next = self.next_start.lock().await;
                let start = (*next).max(Instant::now());
                *next = start + interval;
                start
            };
            tokio::time::sleep_until(start).await;
        }
        let now = self.in_flight.fetch_add(1, Ordering::SeqCst) + 1;
        self.peak.fetch_max(now, Ordering::SeqCst);
        Permit {
            _slot: slot,
            in_flight: Arc::clone(&self.in_flight),
        }
    }

    /// Requests in flight right now.
    pub fn in_flight(&self) -> usize {
        self.in_flight.load(Ordering::SeqCst)
    }

    /// The most requests ever in flight at once.
    pub fn peak_in_flight(&self) -> usize {
        self.peak.load(Ordering::SeqCst)
    }
}

/// Every model server's gateway, by the server's name in `[models]`.
#[derive(Debug, Default, Clone)]
pub struct Gateways {
    by_name: HashMap<String, Arc<ModelGateway>>,
}

impl Gateways {
    /// One gateway per model server (the `[models.NAME]` sections of an agent graph).
    pub fn for_models(models: &BTreeMap<String, ModelConfig>) -> Self {
        Gateways {
            by_name: models
                .iter()
                .map(|(n, m)| {
                    (
                        n.clone(),
                        Arc::new(ModelGateway::new(n.clone(), m.max_in_flight, m.rate_per_s)),
                    )
                })
                .collect(),
        }
    }

    /// The gateway of model server `name`.
    pub fn get(&self, name: &str) -> Option<Arc<ModelGateway>> {
        self.by_name.get(name).cloned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test(start_paused = true)]
    async fn never_more_than_the_limit_in_flight() {
        let g = Arc::new(ModelGateway::new("m", 3, None));
        let tasks: Vec<_> = (0..20)
            .map(|_| {
                let g = Arc::clone(&g);
                tokio::spawn(async move {
                    let _p = g.acquire().await;
                    tokio::time::sleep(Duration::from_millis(10)).await;
                })
            })
            .collect();
        for t in tasks {
            t.await.unwrap();
        }
        assert_eq!(g.peak_in_flight(), 3);
        assert_eq!(g.in_flight(), 0);
    }

    #[tokio::test(start_paused = true)]
    async fn the_rate_limit_spaces_out_starts() {
        let g = ModelGateway::new("m", 100, Some(10.0));
        let t0 = Instant::now();
        for _ in 0..5 {
            drop(g.acquire().await);
        }
        // Starts at 0, 100, 200, 300 and 400 ms.
        assert_eq!(t0.elapsed(), Duration::from_millis(400));
    }
}
